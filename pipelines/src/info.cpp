#include "conform/pipelines/info.h"

#include "conform/core/io.h"
#include "conform/core/mesh.h"

namespace conform {

InfoResult run_info(const InfoOptions& options) {
  ReadOptions read;
  read.non_finite = NonFinitePolicy::kKeep;  // count them instead of refusing the file
  read.cad = options.cad;
  ReadReport report;
  const Mesh mesh = read_geometry(options.path, read, &report);

  InfoResult result;
  result.path = options.path;
  result.format = file_extension(options.path);
  result.points = mesh.vertices.size();
  result.faces = mesh.faces.size();
  result.has_normals = mesh.has_normals();
  result.non_finite = count_non_finite(mesh);
  result.box = bounding_box(mesh);
  result.surface_area_mm2 = surface_area(mesh);
  result.warnings = report.warnings;
  result.cad = report.cad;
  return result;
}

}  // namespace conform
