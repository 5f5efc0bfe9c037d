#pragma once
// Fine ICP of a scan against its reference: point-to-point, point-to-plane, point-to-surface or plane-to-plane
// (generalized ICP) (icp_options.h),
// with a maximum distance, trimming and a robust kernel, stopping on physical tolerances, optionally with locked
// degrees of freedom, and reporting what the scan does not constrain (degeneracy.h).
//
//   IcpReference reference(cad_mesh);
//   IcpOptions options;  options.method = IcpMethod::kPointToSurface;  options.max_correspondence_distance_mm = 5;
//   const IcpResult r = icp(scan_points, reference, T_ref_scan_guess, options);
//   if (!r.converged) ...  // r.termination says why
//
// Runs in parallel (OpenMP); sums are taken over fixed blocks in a fixed order, so the result does not depend on the
// number of threads.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/registration/degeneracy.h"
#include "conform/registration/icp_options.h"
#include "conform/registration/icp_reference.h"

namespace conform {

struct IcpResult {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // p_ref = T_ref_scan * p_scan
  bool converged = false;
  IcpTermination termination = IcpTermination::kFailure;
  int iterations = 0;  // steps taken
  // The figures below are those of the last pairs found: at the start of the last step when converged (that step
  // moved less than the tolerances), at the final pose otherwise.
  // RMS of the inliers' distances (Euclidean to the nearest point for point-to-point, along the reference normal for
  // point-to-plane and plane-to-plane, to the surface for point-to-surface), unweighted, mm.
  double rms_mm = 0.0;
  std::size_t inliers = 0;           // pairs within the maximum distance that survived trimming
  double inlier_fraction = 0.0;      // inliers / scan points
  // The robust kernel's scale in the last step, 1.4826 median |r| (0 without a kernel); while ICP creeps its kernel
  // is wider (twice the last step's motion, docs/align.md), which a converged last step never is.
  double kernel_scale_mm = 0.0;
  double last_rotation_rad = 0.0;    // the last step's rotation
  double last_translation_mm = 0.0;  // the last step's displacement of the scan's centroid
  // The last step in units of the pose's predicted std (its Mahalanobis length, convergence.h Eq. (1)); converged
  // when below IcpOptions::convergence_std_fraction.
  double last_step_std = 0.0;
  DegeneracyReport degeneracy;
};

// scan: points in the scan frame, mm, finite. T_ref_scan_init: the start. Throws conform::Error when the options are
// not valid, the scan is empty or not finite, or point-to-surface is asked of a reference without faces.
IcpResult icp(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
              const Eigen::Isometry3d& T_ref_scan_init, const IcpOptions& options);

// Rotation angle (rad) and translation (mm) of a transform; the size of an ICP step or of a pose error.
double rotation_angle(const Eigen::Isometry3d& T);

}  // namespace conform
