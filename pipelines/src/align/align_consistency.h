#pragma once
// The inverse-consistency check of a fine fit against a cloud reference: the same fit with the roles swapped (the
// reference's points fitted to the scan, from the inverse of the pose found) must land where the forward fit did.
// Against another scan the forward fit is biased by what the linearised covariance cannot see: the reference's
// noise at its steep, sparsely sampled features tilts its normals the same way along a whole edge, and the fit
// absorbs it (docs/align.md, "Is the predicted std honest?"). Swapping the roles moves that bias to the other
// cloud, so the two poses differ by about its size; the difference is added to the pose's covariance as a bias.

#include <vector>

#include <Eigen/Geometry>

#include "conform/registration/degeneracy.h"
#include "conform/registration/icp.h"

namespace conform::detail {

struct InverseConsistency {
  bool ran = false;  // false when the reverse fit did not converge (nothing is added then)
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // the pose the reverse fit gives
  // The forward pose relative to the reverse one in the covariance's coordinates (rad about the axes through the
  // covariance's centre, then the centre's displacement, mm): degeneracy.h.
  Vector6d twist = Vector6d::Zero();
  double largest_displacement_mm = 0.0;  // of a scan point between the two poses
};

// The reverse fit: `reference` (a cloud, reference frame) against `scan` (its frame) from forward.T_ref_scan's
// inverse, with `fine`'s method and distance, the overlap estimated (the reference covers more than the scan), at
// most as many reference points as the scan has (an even stride). `centre`: the covariance's (degeneracy.centre).
InverseConsistency inverse_consistency(const std::vector<Eigen::Vector3d>& scan,
                                       const std::vector<Eigen::Vector3d>& reference, const IcpResult& forward,
                                       const IcpOptions& fine);

// The covariance with the consistency's twist added as a bias (its outer product), std recomputed.
void add_consistency_bias(const InverseConsistency& consistency, DegeneracyReport& degeneracy);

}  // namespace conform::detail
