#pragma once
// What the coarse stage of `conform align` sees of a reference mesh: points spread over its surface by area at the
// scan's own spacing, with the faces' normals, whatever the tessellation. A CAD tessellation has vertices only on its
// faces' boundaries and long thin triangles: features (FPFH) and the starts' inlier scoring over its vertices see the
// rims, not the faces, and a scan over a flat face finds no reference point near it. Fine ICP still measures to the
// mesh itself.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform::detail {

// At most this many surface points (a reference far larger than the scan is sampled coarser than the scan).
inline constexpr std::size_t kCoarseReferenceMaxPoints = 400000;

// Surface points (vertices and unit normals, no faces) of `reference` (a mesh with faces) at about `spacing_mm`
// apart (> 0), area-weighted (core/mesh_sampling.h): at least 1000, at most kCoarseReferenceMaxPoints. Throws
// conform::Error for a spacing that is not > 0 or a mesh without faces of positive area.
Mesh coarse_reference(const Mesh& reference, double spacing_mm);

// The spacing of the scan the coarse stage is given (median nearest-neighbour distance), mm; 0 for < 2 points.
double scan_spacing(const std::vector<Eigen::Vector3d>& scan);

}  // namespace conform::detail
