#pragma once
// A smooth, doubly curved test surface z(x, y) and a rectangular grid sampled from it (2.5 mm along x, 2 mm along y),
// shared by the Bézier patch and network tests.

#include <cmath>

#include <Eigen/Core>

#include "conform/fitting/surface_grid.h"

namespace conform::test {

inline Eigen::Vector3d wavy(double x, double y) {
  return {x, y, 3.0 * std::sin(0.1 * x) * std::cos(0.13 * y) + 0.01 * x * y};
}

inline SurfaceGrid wavy_grid(int rows, int cols) {
  SurfaceGrid grid;
  grid.rows = rows, grid.cols = cols;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) grid.points.push_back(wavy(2.5 * c, 2.0 * r));
  }
  return grid;
}

}  // namespace conform::test
