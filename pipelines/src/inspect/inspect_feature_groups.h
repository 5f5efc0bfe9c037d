#pragma once
// `conform inspect`'s features: a hole or boss is the cylinder, not the B-rep face. A CAD kernel often splits a full
// cylinder into two or more faces (OpenCASCADE's closed-face split, most STEP exporters' half cylinders); the faces
// that lie on one cylinder (same axis and radius within the tolerances below, same side outside) are one feature,
// measured on all their points.

#include <cstddef>
#include <vector>

#include "conform/core/cad_faces.h"

namespace conform::detail {

// Two cylindrical faces are on one cylinder when their axes are parallel within this angle, each axis passes within
// kFeatureSameAxisMm of the other's points, and their radii differ by at most kFeatureSameRadiusMm: far below any
// machined difference, far above the rounding of a STEP file's numbers.
constexpr double kFeatureSameAxisRad = 1e-5;  // 0.00057 deg
constexpr double kFeatureSameAxisMm = 1e-3;
constexpr double kFeatureSameRadiusMm = 1e-3;

// The cylindrical faces grouped by cylinder: per feature the indices into `faces` (ascending), features in the order of
// their first face. A cylinder of one face is a feature of one face.
std::vector<std::vector<std::size_t>> cylinder_features(const std::vector<CadFace>& faces);

// The feature's nominal as one face: the cylinder of its first face, the sum of the areas and triangles, the
// area-weighted centre, and the axis point nearest that centre as its origin.
CadFace feature_nominal(const std::vector<CadFace>& faces, const std::vector<std::size_t>& group);

}  // namespace conform::detail
