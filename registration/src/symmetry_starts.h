#pragma once
// The reference's candidate symmetries as coarse starts (rank_starts, multi_start.h): the best pose turned so that a
// symmetric reference, or the part of it the scan covers, would look the same, for the ambiguity test to find.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/registration/coarse_pca.h"
#include "conform/registration/multi_start.h"
#include "conform/registration/thin_walls.h"

namespace conform::detail {

// The best pose followed by a turn of the reference about its principal axes through its centroid: half turns about
// each axis, and about an axis whose two companions spread alike (within `similarity`: a near-axisymmetric part, a
// flange, a square plate) every 15 deg, and half turns about the axes between those companions every 15 deg. An
// n-fold part (n bolt holes) has its other indices n-fold apart, and a turn within half of that of each reaches it
// (n <= 12); a square plate is also its own mirror across a diagonal, which only the half turn about that diagonal
// (not a principal axis) maps onto itself. Labelled "<best> turned N deg about ...". None for fewer than 3 points.
std::vector<CoarseStart> symmetry_starts(const StartReport& best, const std::vector<Eigen::Vector3d>& reference,
                                         double similarity);

// Each base pose slid along the reference's longest principal axis, where the reference is at least three times as
// long as it is wide and half as long again as the scan at that pose (a stretch of a long profile, tube or bar): by
// every multiple of the step that keeps the scan's extent along the axis within the reference's, at most max_shifts
// a base (the step widened to fit), labelled "<base> slid N mm along reference axis 1". A long part whose features
// are the only thing that fixes the stretch's place (holes along a profile) has nothing for a rotation-invariant
// descriptor to tell apart along it, and ICP finds a feature only within about its size. None for fewer than 3
// points or a step that is not positive.
std::vector<CoarseStart> slide_starts(const std::vector<StartReport>& bases,
                                      const std::vector<Eigen::Vector3d>& reference,
                                      const std::vector<Eigen::Vector3d>& scan, double step_mm, std::size_t max_shifts);

// Each base pose shifted through each thin wall: by -t, 0 or +t along each of the wall's normal directions (reference
// frame), every combination but no shift (up to 26 a wall and base), labelled "<base> shifted through a 5.0 mm wall
// (+1, 0, -1)". A scan of one side of a plate shifted by its thickness lies on the far face and fits almost as well.
std::vector<CoarseStart> wall_starts(const std::vector<StartReport>& bases, const std::vector<ThinWall>& walls);

}  // namespace conform::detail
