#pragma once
// The reference's candidate symmetries as coarse starts (rank_starts, multi_start.h): the best pose turned so that a
// symmetric reference, or the part of it the scan covers, would look the same, for the ambiguity test to find.

#include <vector>

#include <Eigen/Core>

#include "conform/registration/coarse_pca.h"
#include "conform/registration/multi_start.h"

namespace conform::detail {

// The best pose followed by a turn of the reference about its principal axes through its centroid: half turns about
// each axis, and about an axis whose two companions spread alike (within `similarity`: a near-axisymmetric part, a
// flange, a square plate) every 15 deg, and half turns about the axes between those companions every 15 deg. An
// n-fold part (n bolt holes) has its other indices n-fold apart, and a turn within half of that of each reaches it
// (n <= 12); a square plate is also its own mirror across a diagonal, which only the half turn about that diagonal
// (not a principal axis) maps onto itself. Labelled "<best> turned N deg about ...". None for fewer than 3 points.
std::vector<CoarseStart> symmetry_starts(const StartReport& best, const std::vector<Eigen::Vector3d>& reference,
                                         double similarity);

}  // namespace conform::detail
