#pragma once
// The rigid transform that best maps one point set onto another in the least-squares sense, in closed form:
// Horn's unit-quaternion method (Horn 1987, "Closed-form solution of absolute orientation using unit quaternions").
// The step of point-to-point ICP (Besl & McKay 1992) and the solver of user-given point pairs.

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct HornResult {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // minimises sum w_i |T p_scan_i - p_ref_i|^2
  // False when the rotation is not determined: fewer than 3 points of non-zero weight, or all of them (nearly) on one
  // line (the largest two eigenvalues of Horn's 4x4 matrix coincide), so that any rotation about that line fits.
  bool well_posed = false;
};

// scan[i] corresponds to ref[i]; weights (empty: all 1) must be >= 0 and one per pair. Sums are taken relative to the
// weighted centroids, in double. Throws conform::Error when the sizes differ or a weight is negative or not finite.
HornResult horn_transform(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& ref,
                          const std::vector<double>& weights = {});

}  // namespace conform
