#pragma once
// Issue 13's near-symmetric part: the ribbed plate (ribbed_plate.h) with a boss near one corner. The plain plate is
// symmetric under a half turn about z, so a partial scan of it fits two poses equally well; the boss makes the pose
// unique, by a small share of the surface (the AlignMatrix tests and bench/align_peers_bench.cpp's mesh pair).

#include "conform/core/mesh.h"
#include "conform/datasets/ribbed_plate.h"

namespace conform {

// The boss's height at (x, y), mm: 4 mm high, flat within 8 mm of (-70, 45), a 2 mm smoothstep ramp down to 0 at
// 10 mm.
double ribbed_plate_boss_height(double x_mm, double y_mm);

// The plate with the boss as a height-field mesh on a regular grid of ~`spacing_mm` (the grid's nodes at both ends),
// two triangles a cell, counter-clockwise seen from above. Throws conform::Error for invalid options or a spacing
// that is not positive.
Mesh ribbed_boss_plate_mesh(const RibbedPlateOptions& options, double spacing_mm);

}  // namespace conform
