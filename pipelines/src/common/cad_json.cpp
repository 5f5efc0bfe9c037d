#include "conform/pipelines/common/cad_json.h"

#include <cmath>

#include "conform/pipelines/common/json_values.h"

namespace conform {

nlohmann::json cad_json(const std::vector<CadReport>& reports) {
  nlohmann::json list = nlohmann::json::array();
  for (const CadReport& r : reports) {
    nlohmann::json bodies = nlohmann::json::array();
    for (const CadBody& b : r.bodies) {
      bodies.push_back({{"kind", to_string(b.kind)},
                        {"faces", b.faces},
                        {"triangles", b.triangles},
                        {"failed_faces", b.failed_faces},
                        {"box_min_mm", b.box_min_mm},
                        {"box_max_mm", b.box_max_mm},
                        {"volume_mm3", b.volume_mm3},
                        {"flipped", b.flipped}});
    }
    list.push_back({{"file", r.path},
                    {"format", r.format},
                    {"file_unit", r.file_unit},
                    {"mm_per_file_unit", r.mm_per_file_unit},
                    {"deflection_mm", r.deflection_mm},
                    {"angular_deflection_deg", r.angular_deflection_rad * 180.0 / M_PI},
                    {"faces", r.faces},
                    {"triangles", r.triangles},
                    {"vertices", r.vertices},
                    {"bodies", bodies},
                    {"saved_mesh", json_path_or_null(r.saved_mesh_path)}});
  }
  return list;
}

}  // namespace conform
