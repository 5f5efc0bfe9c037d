#include "conform/pipelines/info/info.h"

#include <cmath>

#include "common/cad_inputs.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/mesh.h"
#include "conform/core/units.h"

namespace conform {

InfoResult run_info(const InfoOptions& options) {
  ReadOptions read;
  read.non_finite = NonFinitePolicy::kKeep;  // count them instead of refusing the file
  read.cad = options.cad;
  ReadReport report;
  Mesh mesh = read_geometry(options.path, read, &report);
  InfoResult result;
  if (!(options.mm_per_unit > 0.0) || !std::isfinite(options.mm_per_unit)) {
    throw Error("millimetres per unit must be finite and > 0");
  }
  if (options.mm_per_unit != 1.0 && !detail::cad_keeps_its_units(report, options.mm_per_unit, result.warnings)) {
    scale_in_place(mesh, options.mm_per_unit);
  }
  result.path = options.path;
  result.format = file_extension(options.path);
  result.points = mesh.vertices.size();
  result.faces = mesh.faces.size();
  result.has_normals = mesh.has_normals();
  result.non_finite = count_non_finite(mesh);
  result.box = bounding_box(mesh);
  result.surface_area_mm2 = surface_area(mesh);
  result.warnings.insert(result.warnings.begin(), report.warnings.begin(), report.warnings.end());
  result.cad = report.cad;
  return result;
}

}  // namespace conform
