#pragma once
// Whether a path of rows closes on itself, as the S-ICP checks, the surface misfit check and the trajectory error read
// it: the gap between its last and first row is at most three median row spacings.

#include <vector>

#include <Eigen/Core>

#include "conform/core/median.h"

namespace conform::detail {

inline bool rows_close(const std::vector<Eigen::Vector3d>& rows) {
  if (rows.size() < 3) return false;
  std::vector<double> spacing;
  spacing.reserve(rows.size() - 1);
  for (std::size_t i = 1; i < rows.size(); ++i) spacing.push_back((rows[i] - rows[i - 1]).norm());
  return (rows.back() - rows.front()).norm() <= 3.0 * median(spacing);
}

}  // namespace conform::detail
