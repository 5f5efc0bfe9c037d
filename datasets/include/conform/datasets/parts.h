#pragma once
// Two more test parts with exact geometry, beside the tube (tube.h): a box-like part with features that fix all six
// degrees of freedom, and a free-form surface. Millimetres; meshed at a target edge length; optional seeded noise.
//
// The box part ("stepped block"), closed, faces wound counter-clockwise seen from outside:
//   an L-shaped profile in the x-z plane, extruded along y in [-40, 40]:
//     (-90, 0) -> (90, 0) -> (90, 25) -> (70, 45) -> (20, 45) -> (20, 20) -> (-90, 20)
//   i.e. a low part (z up to 20) for x < 20, a riser at x = 20, a high part (z up to 45) with a 45-degree chamfer
//   from (70, 45) down to (90, 25); plus a rectangular boss on the low part, x in [-70, -30], y in [-25, 5],
//   z in [20, 35], off-centre in y so that no rotation maps the part onto itself.
//   Size 180 x 80 x 45 mm, volume 430000 mm^3 (kBoxPartVolumeMm3).
//   Every planar facet is a convex quadrilateral meshed on its own grid; vertices that coincide along shared edges are
//   welded, so facets whose grids differ along an edge meet with T-junctions (no gaps in the geometry).
//
// The free-form surface, open, faces wound counter-clockwise seen from +z:
//   z = freeform_height(x, y) over x in [-100, 100], y in [-75, 75] (formula in parts.cpp): two crossing waves and
//   an off-centre dome, no symmetry. A regular grid in x and y at the edge length, each cell cut along its shorter
//   diagonal.

#include <cstdint>
#include <string>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform {

struct PartOptions {
  double edge_mm = 4.0;    // target edge length of the grids (> 0); at most 2e7 triangles (edge >= ~0.08 mm)
  double noise_mm = 0.0;   // Gaussian noise along each vertex's normal, sigma (>= 0)
  std::uint64_t seed = 1;  // of the noise
  // Store per-vertex normals of the noise-free mesh: the box's area-weighted from its faces, the free-form surface's
  // exact. Noise moves the vertices, not these normals.
  bool vertex_normals = true;

  // False (and why) for an edge that is not > 0 (or too small for the part's size), negative or non-finite noise.
  bool IsValid(std::string* error) const;
};

inline constexpr double kBoxPartVolumeMm3 = 430000.0;

// Throw conform::Error when the options are not valid.
Mesh box_part(const PartOptions& options);
Mesh freeform_surface(const PartOptions& options);

// The free-form surface's height, mm, and its unit normal (pointing to +z).
double freeform_height(double x_mm, double y_mm);
Eigen::Vector3d freeform_normal(double x_mm, double y_mm);

}  // namespace conform
