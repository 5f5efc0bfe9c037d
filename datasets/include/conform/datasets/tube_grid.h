#pragma once
// How generate_tube divides the surface: rows of vertices at constant z, each row shifted by half a column against
// its neighbours, so that the triangles between two rows are near-equilateral (the uniform triangulation a scanner's
// remeshing gives). A patch keeps straight azimuth borders (its odd rows carry an extra vertex on each border);
// a closed tube's rows wrap around without a duplicated vertex.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/datasets/tube_options.h"

namespace conform {

struct TubeGrid {
  bool closed = false;   // the arc is a full turn
  int columns = 0;       // column intervals across the arc (closed: vertices per row)
  int rows = 0;          // row intervals along the axis (rows + 1 rows of vertices)
  double edge_mm = 0.0;  // the target edge length used (options.edge_mm, or derived from vertex_count)
  double theta_start_rad = 0.0;
  double column_step_rad = 0.0;  // arc / columns
  double z_start_mm = 0.0;       // -length / 2
  double row_step_mm = 0.0;      // length / rows, about edge * sqrt(3) / 2

  std::int64_t vertex_count() const;
  std::int64_t face_count() const;
};

// The layout for valid geometry options (radius, length, arc, edge or vertex_count).
TubeGrid tube_grid(const TubeOptions& options);
// (theta rad, z mm) of every vertex, row by row, theta increasing within a row.
std::vector<Eigen::Vector2d> tube_grid_parameters(const TubeGrid& grid);
// Faces wound counter-clockwise in (theta, z) for the outer surface (normal away from the axis), the other way for
// the inner surface.
std::vector<Face> tube_grid_faces(const TubeGrid& grid, TubeSurface surface);

}  // namespace conform
