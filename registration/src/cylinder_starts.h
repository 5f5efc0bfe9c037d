#pragma once
// Coarse starts for a tube from the axes of cylinders fitted to the scan and to the reference (coarse.h): where FPFH
// finds no hypothesis because a cylinder's features are all alike, and a partial arc's principal axes are not the
// tube's.

#include <vector>

#include <Eigen/Core>

#include "conform/registration/coarse_pca.h"

namespace conform::detail {

// When a cylinder fits the scan and one of about the same radius (within kCylinderRadiusShare) fits the reference
// (fitting/cylinder.h, on at most 20,000 points of each, seeded): the scan's axis turned onto the reference's, both
// ways, the scan's axis point (nearest its inliers' centroid) onto the reference's (nearest its own), turned about
// the axis in steps that move the scan's farthest point from the axis by turn_step_mm (at least 0.5 deg), labelled
// "cylinder axis +|- turn N.N" and marked for screening (CoarseStart::screen): what fixes the turn (a weld bead a few
// mm wide, a cut end) is within a quick probe's reach of one of them. Where along the axis the scan belongs is for
// the probes to find (the slides of multi_start.h). None when either fit fails or the radii differ.
std::vector<CoarseStart> cylinder_starts(const std::vector<Eigen::Vector3d>& scan,
                                         const std::vector<Eigen::Vector3d>& reference,
                                         const std::vector<Eigen::Vector3d>& reference_normals, double turn_step_mm);

}  // namespace conform::detail
