#include "conform/fitting/surface_grid.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>

#include "conform/core/error.h"

namespace conform {

SurfaceGrid surface_grid_from_table(const CsvTable& table) {
  const std::size_t row_col = table.column("row"), col_col = table.column("col");
  const std::size_t x = table.column("x_mm"), y = table.column("y_mm"), z = table.column("z_mm");
  std::map<std::pair<std::int64_t, std::int64_t>, std::size_t> where;  // (row, col) -> table row
  std::map<std::int64_t, std::int64_t> row_width;
  std::int64_t max_row = -1, max_col = -1;
  for (std::size_t i = 0; i < table.rows(); ++i) {
    const std::int64_t r = table.integer(i, row_col), c = table.integer(i, col_col);
    const std::string at = table.path + ":" + std::to_string(table.line_numbers[i]) + ": ";
    if (r < 0 || c < 0) throw Error(at + "negative row or col (" + std::to_string(r) + ", " + std::to_string(c) + ")");
    if (r > 100000 || c > 100000) throw Error(at + "row or col above 100000");
    if (!where.emplace(std::make_pair(r, c), i).second) {
      throw Error(at + "grid point (row " + std::to_string(r) + ", col " + std::to_string(c) + ") appears twice");
    }
    row_width[r] = std::max(row_width[r], c + 1);
    max_row = std::max(max_row, r);
    max_col = std::max(max_col, c);
  }
  if (max_row < 1 || max_col < 1) throw Error(table.path + ": a grid needs at least 2 rows and 2 columns");
  for (std::int64_t r = 0; r <= max_row; ++r) {
    const auto width = row_width.find(r);
    if (width == row_width.end()) throw Error(table.path + ": grid row " + std::to_string(r) + " is missing");
    if (width->second != max_col + 1) {
      throw Error(table.path + ": ragged grid: row " + std::to_string(r) + " has columns up to " +
                  std::to_string(width->second - 1) + ", other rows up to " + std::to_string(max_col));
    }
  }
  SurfaceGrid grid;
  grid.rows = static_cast<int>(max_row + 1);
  grid.cols = static_cast<int>(max_col + 1);
  grid.points.resize(static_cast<std::size_t>(grid.rows) * static_cast<std::size_t>(grid.cols));
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const auto it = where.find({r, c});
      if (it == where.end()) {
        throw Error(table.path + ": hole in the grid: row " + std::to_string(r) + ", col " + std::to_string(c) +
                    " is missing");
      }
      grid.at(r, c) = {table.number(it->second, x), table.number(it->second, y), table.number(it->second, z)};
    }
  }
  return grid;
}

CsvWriter surface_grid_table(const SurfaceGrid& grid, int decimals) {
  CsvWriter out({"row", "col", "x_mm", "y_mm", "z_mm"}, decimals);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const Eigen::Vector3d& p = grid.at(r, c);
      out.cell(r).cell(c).cell(p.x()).cell(p.y()).cell(p.z());
      out.end_row();
    }
  }
  return out;
}

}  // namespace conform
