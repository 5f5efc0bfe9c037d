#pragma once
// Length units of input files. conform computes in millimetres; a file in metres (a range sensor's cloud) or inches
// is scaled on reading (`--units m`), never silently.

#include <string>

#include "conform/core/cloud.h"
#include "conform/core/mesh.h"

namespace conform {

// Millimetres per unit for "mm", "cm", "m", "in" (case-insensitive). Throws conform::Error naming the unit and the
// accepted ones otherwise.
double millimetres_per_unit(const std::string& unit);

// Coordinates multiplied by `factor` (normals unchanged). factor must be finite and > 0.
void scale_in_place(Cloud& cloud, double factor);
void scale_in_place(Mesh& mesh, double factor);

}  // namespace conform
