#include "conform/datasets/tube_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace conform {

namespace {

// Equilateral triangles of side e stack in rows e * sqrt(3) / 2 apart.
constexpr double kRowHeightPerEdge = 0.86602540378443864676;

// Vertex positions of a row in half-column steps k (theta = theta_start + k * column_step / 2). Even rows sit on the
// columns, odd rows between them; a patch's odd rows also hold the two border points.
std::vector<int> row_half_steps(const TubeGrid& grid, int row) {
  std::vector<int> k;
  const bool odd = row % 2 == 1;
  if (grid.closed) {
    for (int j = 0; j < grid.columns; ++j) k.push_back(2 * j + (odd ? 1 : 0));
  } else if (!odd) {
    for (int j = 0; j <= grid.columns; ++j) k.push_back(2 * j);
  } else {
    k.push_back(0);
    for (int j = 0; j < grid.columns; ++j) k.push_back(2 * j + 1);
    k.push_back(2 * grid.columns);
  }
  return k;
}

struct RowVertex {
  int k;
  std::int32_t index;
};

std::vector<RowVertex> row_vertices(const TubeGrid& grid, int row, std::int32_t first_index) {
  std::vector<RowVertex> out;
  for (int k : row_half_steps(grid, row)) out.push_back({k, first_index + static_cast<std::int32_t>(out.size())});
  // A closed row ends where it began, one turn (2 * columns half-steps) later.
  if (grid.closed) out.push_back({out.front().k + 2 * grid.columns, out.front().index});
  return out;
}

// Zips two neighbouring rows into triangles, each time adding the shorter of the two possible diagonals (the
// smaller azimuth offset, since the rows are a constant step apart in z): the staggered pattern inside, and right
// triangles rather than long slivers at a patch's borders. (lower[l], lower[l + 1], upper[u]) is counter-clockwise in
// (theta, z).
void zip_rows(const std::vector<RowVertex>& lower, const std::vector<RowVertex>& upper, bool inner,
              std::vector<Face>& faces) {
  std::size_t l = 0;
  std::size_t u = 0;
  while (l + 1 < lower.size() || u + 1 < upper.size()) {
    const bool take_lower =
        u + 1 == upper.size() ||
        (l + 1 < lower.size() && std::abs(lower[l + 1].k - upper[u].k) <= std::abs(upper[u + 1].k - lower[l].k));
    Face face = take_lower ? Face{lower[l].index, lower[l + 1].index, upper[u].index}
                           : Face{lower[l].index, upper[u + 1].index, upper[u].index};
    if (inner) std::swap(face[1], face[2]);
    faces.push_back(face);
    (take_lower ? l : u) += 1;
  }
}

}  // namespace

std::int64_t TubeGrid::vertex_count() const {
  const std::int64_t c = columns;
  const std::int64_t vertex_rows = std::int64_t{rows} + 1;
  if (closed) return vertex_rows * c;
  const std::int64_t odd_rows = vertex_rows / 2;
  return (vertex_rows - odd_rows) * (c + 1) + odd_rows * (c + 2);
}

std::int64_t TubeGrid::face_count() const {
  const std::int64_t c = columns;
  return std::int64_t{rows} * (closed ? 2 * c : 2 * c + 1);
}

TubeGrid tube_grid(const TubeOptions& options) {
  TubeGrid grid;
  grid.closed = options.arc_rad >= 2.0 * M_PI;
  const double arc = grid.closed ? 2.0 * M_PI : options.arc_rad;
  const double arc_length = options.radius_mm * arc;
  grid.edge_mm = options.edge_mm;
  if (options.vertex_count > 0) {
    // One vertex per e * (e sqrt(3) / 2) of surface.
    const double area = arc_length * options.length_mm;
    grid.edge_mm = std::sqrt(area / (static_cast<double>(options.vertex_count) * kRowHeightPerEdge));
  }
  const int min_columns = grid.closed ? 3 : 1;
  grid.columns = std::max(min_columns, static_cast<int>(std::lround(arc_length / grid.edge_mm)));
  grid.rows = std::max(1, static_cast<int>(std::lround(options.length_mm / (grid.edge_mm * kRowHeightPerEdge))));
  grid.theta_start_rad = grid.closed ? options.arc_center_rad - M_PI : options.arc_center_rad - 0.5 * arc;
  grid.column_step_rad = arc / grid.columns;
  grid.z_start_mm = -0.5 * options.length_mm;
  grid.row_step_mm = options.length_mm / grid.rows;
  return grid;
}

std::vector<Eigen::Vector2d> tube_grid_parameters(const TubeGrid& grid) {
  std::vector<Eigen::Vector2d> params;
  params.reserve(static_cast<std::size_t>(grid.vertex_count()));
  const double half_step = 0.5 * grid.column_step_rad;
  for (int i = 0; i <= grid.rows; ++i) {
    const double z = grid.z_start_mm + i * grid.row_step_mm;
    for (int k : row_half_steps(grid, i)) params.emplace_back(grid.theta_start_rad + k * half_step, z);
  }
  return params;
}

std::vector<Face> tube_grid_faces(const TubeGrid& grid, TubeSurface surface) {
  std::vector<Face> faces;
  faces.reserve(static_cast<std::size_t>(grid.face_count()));
  const bool inner = surface == TubeSurface::kInner;
  std::int32_t first = 0;
  std::vector<RowVertex> lower = row_vertices(grid, 0, first);
  for (int i = 1; i <= grid.rows; ++i) {
    first += static_cast<std::int32_t>(row_half_steps(grid, i - 1).size());
    std::vector<RowVertex> upper = row_vertices(grid, i, first);
    zip_rows(lower, upper, inner, faces);
    lower = std::move(upper);
  }
  return faces;
}

}  // namespace conform
