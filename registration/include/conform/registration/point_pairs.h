#pragma once
// Alignment from point pairs a user gives: scanner markers or reference targets measured in both frames (>= 3, not
// on one line). Horn's closed form (horn.h), with the residual of every pair so that a mistyped pair shows.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct PointPair {
  Eigen::Vector3d scan = Eigen::Vector3d::Zero();       // mm, scan frame
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // mm, reference frame
};

struct PointPairsResult {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  std::vector<double> residuals_mm;  // |T_ref_scan * scan_i - reference_i|, one per pair, in the given order
  double rms_mm = 0.0;
  double max_residual_mm = 0.0;
  std::size_t worst_pair = 0;  // index of the largest residual
};

// Throws conform::Error for fewer than 3 pairs, a non-finite coordinate, or pairs whose scan points lie on one line
// (the rotation about it is then free).
PointPairsResult align_point_pairs(const std::vector<PointPair>& pairs);

}  // namespace conform
