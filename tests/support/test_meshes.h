#pragma once
// Closed meshes with a known surface, for tests: a latitude-longitude sphere whose radius may vary with direction.

#include <cmath>
#include <cstdint>
#include <functional>

#include "conform/core/constants.h"
#include "conform/core/mesh.h"

namespace conform::test {

// `rings` latitude bands (>= 2) by `segments` meridians (>= 3); radius(polar, azimuth) in mm, polar 0 at +z.
// The poles are shared by a fan of faces; faces wind outward.
inline Mesh lat_long_sphere(int rings, int segments, const std::function<double(double, double)>& radius) {
  Mesh m;
  m.vertices.emplace_back(0, 0, radius(0, 0));
  for (int i = 1; i < rings; ++i) {
    const double polar = kPi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double az = 2 * kPi * j / segments;
      const double r = radius(polar, az);
      m.vertices.emplace_back(r * std::sin(polar) * std::cos(az), r * std::sin(polar) * std::sin(az),
                              r * std::cos(polar));
    }
  }
  m.vertices.emplace_back(0, 0, -radius(kPi, 0));
  const auto south = static_cast<std::int32_t>(m.vertices.size() - 1);
  auto ring = [&](int i, int j) { return static_cast<std::int32_t>(1 + (i - 1) * segments + (j % segments)); };
  for (int j = 0; j < segments; ++j) {
    m.faces.push_back({0, ring(1, j), ring(1, j + 1)});
    m.faces.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      m.faces.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      m.faces.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  }
  return m;
}

}  // namespace conform::test
