#pragma once
// A scanned tube's own frame (z along its axis, as `generate tube` and the tube-joint frames L and S use), from the
// cylinder fit (fitting/cylinder.h: axis and radius) plus >= 3 markers whose positions are known in the tube frame
// (HandySCAN targets, punch marks), their order giving the correspondence.
//
// The axis fixes 4 of the 6 degrees of freedom (the axis direction and its position across it). The markers fix the
// other two in closed form: the rotation psi about the axis (2D Procrustes of the markers' components across the
// axis) and the shift h along it (the mean of their along-axis differences); both axis signs are tried and the one
// with the smaller marker residual kept. Without markers, rotation about the axis and shift along it are free: the
// result then puts azimuth 0 towards an arbitrary direction and z = 0 at the foot of the points' centroid, and says
// so (`free_about_axis`).

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/fitting/cylinder.h"

namespace conform {

struct TubeReferenceOptions {
  CylinderFitOptions fit;               // the axis fit (threshold, radius bounds, axis prior, seed ...)
  double max_marker_residual_mm = 2.0;  // a marker farther than this from its known position fails the result

  bool IsValid(std::string* error) const;
};

struct TubeReferenceResult {
  bool ok = false;
  std::string termination = "not run";  // "ok", or why not (fit failed, a marker residual too large)
  Eigen::Isometry3d T_tube_scan = Eigen::Isometry3d::Identity();  // p_tube = T_tube_scan * p_scan
  CylinderFitResult fit;
  bool free_about_axis = true;              // no markers: rotation about and shift along the axis are not determined
  std::vector<double> marker_residuals_mm;  // |T_tube_scan * m_scan - m_tube| per marker
  double marker_rms_mm = 0.0;
  double marker_max_mm = 0.0;
};

// Throws conform::Error when the options are invalid, the marker lists differ in length, there are 1 or 2 markers
// (0 or >= 3 are needed), or the markers are degenerate (all on the axis, or coincident along it: the rotation is
// undetermined). The fit's own errors propagate (fitting/cylinder.h).
TubeReferenceResult tube_reference(const std::vector<Eigen::Vector3d>& points,
                                   const std::vector<Eigen::Vector3d>& normals,
                                   const std::vector<Eigen::Vector3d>& markers_scan,
                                   const std::vector<Eigen::Vector3d>& markers_tube,
                                   const TubeReferenceOptions& options = {});

// The closed-form part on its own: given the axis (a point and a unit direction, in the scan), the markers.
// Returns T_tube_scan and writes the residuals.
Eigen::Isometry3d tube_frame_from_markers(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                                          const std::vector<Eigen::Vector3d>& markers_scan,
                                          const std::vector<Eigen::Vector3d>& markers_tube,
                                          std::vector<double>* residuals_mm);

}  // namespace conform
