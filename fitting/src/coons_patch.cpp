#include "conform/fitting/coons_patch.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "conform/core/error.h"

namespace conform {

CoonsPatch::CoonsPatch(BoundaryCurve c0, BoundaryCurve c1, BoundaryCurve d0, BoundaryCurve d1,
                       double corner_tolerance_mm)
    : c0_(std::move(c0)), c1_(std::move(c1)), d0_(std::move(d0)), d1_(std::move(d1)) {
  if (!c0_ || !c1_ || !d0_ || !d1_) throw Error("Coons patch: a boundary curve is missing");
  const std::pair<Eigen::Vector3d, Eigen::Vector3d> corners[4] = {
      {c0_(0.0), d0_(0.0)}, {c0_(1.0), d1_(0.0)}, {c1_(0.0), d0_(1.0)}, {c1_(1.0), d1_(1.0)}};
  for (const auto& [a, b] : corners) {
    if (!((a - b).norm() <= corner_tolerance_mm)) {
      throw Error("Coons patch: boundary curves do not meet at a corner (gap " + std::to_string((a - b).norm()) +
                  " mm)");
    }
  }
}

Eigen::Vector3d CoonsPatch::position(double u, double v) const {
  const Eigen::Vector3d ruled_v = (1.0 - v) * c0_(u) + v * c1_(u);
  const Eigen::Vector3d ruled_u = (1.0 - u) * d0_(v) + u * d1_(v);
  const Eigen::Vector3d bilinear = (1.0 - u) * (1.0 - v) * c0_(0.0) + u * (1.0 - v) * c0_(1.0) +
                                   (1.0 - u) * v * c1_(0.0) + u * v * c1_(1.0);
  return ruled_v + ruled_u - bilinear;
}

SurfaceGrid CoonsPatch::sample(int rows, int cols) const {
  if (rows < 2 || cols < 2) throw Error("Coons patch: sample at least 2 x 2 points");
  SurfaceGrid grid;
  grid.rows = rows;
  grid.cols = cols;
  grid.points.resize(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) grid.at(r, c) = position(double(c) / (cols - 1), double(r) / (rows - 1));
  }
  return grid;
}

namespace {

// A polyline through `points` at equal parameter steps, t in [0, 1].
BoundaryCurve polyline(std::vector<Eigen::Vector3d> points) {
  return [points = std::move(points)](double t) {
    const double s = std::clamp(t, 0.0, 1.0) * static_cast<double>(points.size() - 1);
    const std::size_t k = std::min(static_cast<std::size_t>(s), points.size() - 2);
    const double x = s - static_cast<double>(k);
    return Eigen::Vector3d((1.0 - x) * points[k] + x * points[k + 1]);
  };
}

}  // namespace

CoonsPatch coons_patch_of_border(const SurfaceGrid& grid) {
  if (grid.rows < 2 || grid.cols < 2) throw Error("Coons patch: the grid needs at least 2 x 2 points");
  std::vector<Eigen::Vector3d> first_row, last_row, first_col, last_col;
  for (int c = 0; c < grid.cols; ++c) first_row.push_back(grid.at(0, c)), last_row.push_back(grid.at(grid.rows - 1, c));
  for (int r = 0; r < grid.rows; ++r) first_col.push_back(grid.at(r, 0)), last_col.push_back(grid.at(r, grid.cols - 1));
  return CoonsPatch(polyline(first_row), polyline(last_row), polyline(first_col), polyline(last_col));
}

}  // namespace conform
