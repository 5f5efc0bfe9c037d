#include "conform/evaluation/cad_deviation.h"

#include <cmath>
#include <cstdint>

#include "conform/core/error.h"

namespace conform {

std::size_t to_exact_cad_faces(const std::vector<Eigen::Vector3d>& scan, const CadFaces& cad, double bound_mm,
                               DeviationResult& deviation) {
  if (!(bound_mm >= 0.0) || !std::isfinite(bound_mm)) throw Error("exact CAD faces: the bound must be finite and >= 0");
  if (!deviation.is_signed()) return 0;
  if (deviation.deviation_mm.size() != scan.size() || deviation.closest.size() != scan.size() ||
      deviation.triangle.size() != scan.size() || cad.triangle_face.size() != cad.mesh.faces.size()) {
    throw Error("exact CAD faces: the deviations, the scan and the faces do not match");
  }
  std::vector<char> exact(scan.size(), 0);
  const auto n = static_cast<std::ptrdiff_t>(scan.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    const double on_mesh = deviation.deviation_mm[i];
    const int t = deviation.triangle[i];
    if (std::isnan(on_mesh) || t < 0 || static_cast<std::size_t>(t) >= cad.triangle_face.size()) continue;
    const std::int32_t f = cad.triangle_face[static_cast<std::size_t>(t)];
    if (f < 0 || static_cast<std::size_t>(f) >= cad.faces.size()) continue;
    const CadFace& face = cad.faces[static_cast<std::size_t>(f)];
    if (!is_analytic(face.type)) continue;
    const double d = analytic_signed_distance(face, scan[i]);
    const Eigen::Vector3d normal = analytic_outward_normal(face, scan[i]);
    if (!std::isfinite(d) || !normal.allFinite() || std::abs(d - on_mesh) > bound_mm) continue;
    deviation.deviation_mm[i] = d;
    deviation.closest[i] = scan[i] - d * normal;
    exact[i] = 1;
  }
  std::size_t count = 0;
  for (const char e : exact) count += static_cast<std::size_t>(e);
  return count;
}

}  // namespace conform
