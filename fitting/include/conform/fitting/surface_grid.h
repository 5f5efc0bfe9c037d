#pragma once
// A rectangular grid (matrix) of measured surface points, as a laser sensor sweeps it: rows x cols points, row r and
// column c at at(r, c). Grid files are CSV `row,col,x_mm,y_mm,z_mm` (core/csv.h), one line per point, in any order;
// the grid must be full: every (row, col) of 0..rows-1 x 0..cols-1 exactly once.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/csv.h"

namespace conform {

struct SurfaceGrid {
  int rows = 0;
  int cols = 0;
  std::vector<Eigen::Vector3d> points;  // row-major: points[r * cols + c]

  const Eigen::Vector3d& at(int r, int c) const { return points[static_cast<std::size_t>(r * cols + c)]; }
  Eigen::Vector3d& at(int r, int c) { return points[static_cast<std::size_t>(r * cols + c)]; }
};

// The grid of a table with columns row, col, x_mm, y_mm, z_mm. Throws conform::Error naming the file and the row:
// a negative or duplicated (row, col), a hole (a missing point), a ragged row (fewer columns than the others), or a
// grid smaller than 2 x 2.
SurfaceGrid surface_grid_from_table(const CsvTable& table);
// The grid as a CSV table (row-major order, `decimals` fixed decimals).
CsvWriter surface_grid_table(const SurfaceGrid& grid, int decimals = 6);

}  // namespace conform
