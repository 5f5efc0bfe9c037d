#pragma once
// Closed meshes with a known surface, for tests: a latitude-longitude sphere whose radius may vary with direction, and
// a block with filleted vertical edges tessellated the way CAD exports are (flat faces as few large triangles).

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

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

// A block of size_x x size_y x height mm (centred in x and y, z from 0) whose four vertical edges are filleted with
// `radius`, each fillet tessellated in `chords` strips (a CAD export: 4 for a coarse STL, ~32 at 0.005 mm deflection).
// The flat sides are one rectangle (two triangles) each, tangent to the fillets; the caps are fans from their centre.
// surface_distance() below is the exact distance of a point to this block's side surface.
inline Mesh filleted_block(double size_x, double size_y, double height, double radius, int chords) {
  const double hx = size_x / 2 - radius, hy = size_y / 2 - radius;
  const double cx[4] = {hx, -hx, -hx, hx}, cy[4] = {hy, hy, -hy, -hy};
  std::vector<Eigen::Vector2d> outline;  // counter-clockwise seen from +z
  for (int c = 0; c < 4; ++c) {
    for (int k = 0; k <= chords; ++k) {
      const double a = kPi / 2 * c + kPi / 2 * k / chords;
      outline.emplace_back(cx[c] + radius * std::cos(a), cy[c] + radius * std::sin(a));
    }
  }
  Mesh m;
  const auto n = static_cast<std::int32_t>(outline.size());
  for (const Eigen::Vector2d& p : outline) {
    m.vertices.emplace_back(p.x(), p.y(), 0.0);
    m.vertices.emplace_back(p.x(), p.y(), height);
  }
  m.vertices.emplace_back(0, 0, 0);
  m.vertices.emplace_back(0, 0, height);
  const std::int32_t bottom = 2 * n, top = bottom + 1;
  for (std::int32_t k = 0; k < n; ++k) {
    const std::int32_t b0 = 2 * k, t0 = b0 + 1, b1 = 2 * ((k + 1) % n), t1 = b1 + 1;
    m.faces.push_back({b0, b1, t1});
    m.faces.push_back({b0, t1, t0});
    m.faces.push_back({bottom, b1, b0});
    m.faces.push_back({top, t0, t1});
  }
  return m;
}

// Signed distance (+ outside) of p to the side of filleted_block(size_x, size_y, ., radius, .), for p between the caps.
inline double filleted_block_side_distance(double size_x, double size_y, double radius, const Eigen::Vector3d& p) {
  const double hx = size_x / 2 - radius, hy = size_y / 2 - radius;
  const double dx = std::abs(p.x()) - hx, dy = std::abs(p.y()) - hy;
  if (dx > 0 && dy > 0) return std::hypot(dx, dy) - radius;
  return std::max(dx, dy) - radius;
}

}  // namespace conform::test
