#pragma once
// Two measures of the bias of a fine fit against a cloud reference, neither of which the linearised covariance sees
// (docs/align.md, "Constraint"; docs/measurements/align.md, "Is the predicted std honest?"):
//   - the inverse-consistency check: the same fit with the roles swapped (the reference's points fitted to the
//     scan, from the inverse of the pose found) must land where the forward fit did. The reference's noise at its
//     steep, sparsely sampled features tilts its normals the same way along a whole edge, and the fit absorbs it;
//     swapping the roles moves that bias to the other cloud, so the two poses differ by about its size;
//   - the normal-model spread: the same fit, from the pose found, against the reference with its normals taken over
//     a wider neighbourhood. Against another scan the model of the surface (its normals, from noisy points) is
//     itself uncertain, and the point-to-plane minimum moves with it: on a noisy golden-sample cloud by 0.02-1.5 deg
//     as the neighbourhood goes from 16 to 64 points, where the linearised std said 0.1-0.4 deg.
// Each difference is added to the pose's covariance as a bias (its outer product).

#include <vector>

#include <Eigen/Geometry>

#include "conform/registration/degeneracy.h"
#include "conform/registration/icp.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {

// Where a second fit landed against the forward one.
struct FitDiscrepancy {
  bool ran = false;  // false when the second fit did not converge (nothing is added then)
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // the pose the second fit gives
  // The forward pose relative to the second one in the covariance's coordinates (rad about the axes through the
  // covariance's centre, then the centre's displacement, mm): degeneracy.h.
  Vector6d twist = Vector6d::Zero();
  double largest_displacement_mm = 0.0;  // of a scan point between the two poses
};

// The reverse fit: the reference's points that lie on the part the scan covers (within reach of a scan point at
// the pose found: 10 robust std of the forward fit's residuals plus the scan's point spacing), at most as many as
// the scan has (an even stride), against `scan` from forward.T_ref_scan's inverse, with `fine`'s method and
// distance and the overlap estimated. What the scan did not see is left out: a 38 % overlap scan's swapped fit
// slid 4.4 mm over it (a real bunny pair). `reference`: the cloud as prepared for the forward fit.
FitDiscrepancy inverse_consistency(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                                   const IcpResult& forward, const IcpOptions& fine);

// The forward fit again, from its pose, against the same reference points with PCA normals over
// 64 neighbours (4 times IcpReference's 16).
FitDiscrepancy normal_model_spread(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                                   const IcpResult& forward, const IcpOptions& fine);

// The covariance with the discrepancy's twist added as a bias (its outer product), std recomputed.
void add_bias(const FitDiscrepancy& discrepancy, DegeneracyReport& degeneracy);

}  // namespace conform::detail
