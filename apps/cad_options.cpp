#include "cad_options.h"

#include <cmath>

#include "terminal.h"

namespace conform::app {

void add_cad_options(CLI::App& command, CadReadOptions& cad) {
  command.add_option("--cad-deflection", cad.deflection_mm,
                     "STEP/IGES references: chordal deflection of the tessellation, mm (no triangle farther from the "
                     "CAD surface)");
  command
      .add_option_function<double>(
          "--cad-angle-deg", [&cad](double deg) { cad.angular_deflection_rad = deg * M_PI / 180.0; },
          "STEP/IGES references: angular deflection, deg; default matched to --cad-deflection (the angle of a chord "
          "with that sagitta on a 1 mm radius)")
      ->check(CLI::Range(0.0, 90.0));
}

void print_cad_text(const std::vector<CadReport>& reports, std::FILE* out) {
  for (const CadReport& r : reports) std::fprintf(out, "cad           %s\n", r.summary().c_str());
}

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
                    {"bodies", bodies}});
  }
  return list;
}

}  // namespace conform::app
