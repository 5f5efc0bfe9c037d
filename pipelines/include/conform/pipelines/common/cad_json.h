#pragma once
// How a CAD read is reported in every job's JSON (the `cad` key), shared by the CLI and the Python binding.

#include <vector>

#include <nlohmann/json.hpp>

#include "conform/core/cad.h"

namespace conform {

// [{"file", "format", "file_unit", "mm_per_file_unit", "deflection_mm", "angular_deflection_deg", "faces",
//   "triangles", "vertices", "bodies": [{"kind", "faces", "triangles", "failed_faces", "box_min_mm", "box_max_mm",
//   "volume_mm3", "flipped"}]}]; empty when no input was CAD.
nlohmann::json cad_json(const std::vector<CadReport>& reports);

}  // namespace conform
