#pragma once
// Issue 13's mesh pair (bench/align_peers_bench.cpp): the ribbed plate (datasets/ribbed_plate.h) with a boss near one
// corner, which makes a partial scan's pose unique (the plain plate is symmetric under a half turn about z), as a
// height-field mesh.

#include <algorithm>
#include <cmath>

#include "conform/core/mesh.h"
#include "conform/datasets/ribbed_plate.h"

namespace conform::test {

// The boss: 8 mm radius, 4 mm high, a 2 mm smoothstep ramp, centred at (-70, 45).
inline double boss_height(double x, double y) {
  const double t = std::clamp((10.0 - std::hypot(x + 70.0, y - 45.0)) / 2.0, 0.0, 1.0);
  return 4.0 * t * t * (3.0 - 2.0 * t);
}

// The plate with the boss on a regular grid of ~`spacing` mm, two triangles a cell, counter-clockwise from above.
inline Mesh ribbed_boss_plate_mesh(const RibbedPlateOptions& o, double spacing) {
  const int nx = static_cast<int>(std::lround(o.length_mm / spacing)) + 1;
  const int ny = static_cast<int>(std::lround(o.width_mm / spacing)) + 1;
  Mesh mesh;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const double x = -0.5 * o.length_mm + o.length_mm * i / (nx - 1);
      const double y = -0.5 * o.width_mm + o.width_mm * j / (ny - 1);
      mesh.vertices.emplace_back(x, y, ribbed_plate_height(o, x, y) + boss_height(x, y));
    }
  }
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      mesh.faces.push_back({a, b, d});
      mesh.faces.push_back({a, d, c});
    }
  }
  return mesh;
}

}  // namespace conform::test
