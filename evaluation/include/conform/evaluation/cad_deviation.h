#pragma once
// Deviations measured to the exact faces of a CAD reference (core/cad_faces.h). compute_deviation() measures to the
// tessellation, which lies within its chordal deflection of the faces (its smooth surface too, about as close); this
// then measures each matched scan point whose closest triangle belongs to an analytic face (plane, cylinder, cone,
// sphere, torus) to that face's exact surface: the form and fillets of a machined part read as they are.
//
//   CadFaces cad = read_cad_faces(path, cad_options, &report, &warnings);
//   DeviationResult d = compute_deviation(scan, cad.mesh, {});
//   to_exact_cad_faces(scan, cad, 2.0 * report.deflection_mm, d);

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cad_faces.h"
#include "conform/evaluation/deviation.h"

namespace conform {

// Replaces, in `deviation` (compute_deviation of `scan` against cad.mesh, signed; its `triangle` says which face each
// point's closest triangle belongs to), the deviation and closest point of each matched point whose closest triangle
// lies on an analytic face by the signed distance to that face's surface
// and the foot of the perpendicular on it, when the two distances differ by at most `bound_mm` (the point lies over
// the face: the tessellation is that close to it; beyond the face's trim the untrimmed surface would differ more and
// the tessellation's figure is kept). Points on other faces (B-splines, ...) keep the tessellation's. Returns how
// many points were measured to an exact face. Parallel over the points; the same input gives the same result.
// Throws conform::Error when the sizes do not match or bound_mm is not finite and >= 0.
std::size_t to_exact_cad_faces(const std::vector<Eigen::Vector3d>& scan, const CadFaces& cad, double bound_mm,
                               DeviationResult& deviation);

}  // namespace conform
