#include "conform/pipelines/export/export_json.h"

#include <filesystem>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {
namespace {

// A larger turn between two consecutive frames is a wrist flip or a corner turned on the spot: warned about.
constexpr double kLargeStepDeg = 30.0;

}  // namespace

std::vector<std::string> export_warnings(const ExportJobResult& r) {
  const ToolFrameFigures& f = r.figures;
  const double max_step_deg = f.max_orientation_step_rad / kPi * 180.0;
  std::vector<std::string> warnings;
  if (max_step_deg > kLargeStepDeg) {
    warnings.push_back("the tool turns by " + std::to_string(max_step_deg) +
                       " deg between two consecutive frames (frame " + std::to_string(f.max_step_index) +
                       "): check for a wrist flip (--roll-cone-deg)");
  }
  return warnings;
}

nlohmann::json export_json(const ExportJobOptions& options, const ExportJobResult& r) {
  const ToolFrameFigures& f = r.figures;
  nlohmann::json files = nlohmann::json::array();
  for (const ExportPathFile& file : r.files) {
    files.push_back({{"path", file.path}, {"job", file.job}, {"segments", file.segments}, {"frames", file.frames}});
  }
  return {{"job", r.job},
          {"paths", files},
          {"format", options.format},
          {"segments", r.segments},
          {"frames", r.frames},
          {"targets", r.targets},
          {"parts", r.parts},
          {"max_orientation_step_deg", f.max_orientation_step_rad / kPi * 180.0},
          {"max_orientation_step_frame", f.max_step_index},
          {"parallel_tangents", f.parallel_tangents},
          {"repeated_points", f.repeated_points},
          {"roll_limited", f.roll_limited},
          {"T_base_part", json_of(r.T_base_part)},
          {"warnings", export_warnings(r)},
          {"written", r.written}};
}

void check_export_name(const ExportJobOptions& options) {
  if (!options.program.name.empty()) return;
  ProgramOptions named = options.program;
  named.name = std::filesystem::path(options.out_path).stem().string();
  std::string why;
  if (!named.IsValid(&why)) throw Error("export: " + why + " (the name is --out's stem; give --name)");
}

}  // namespace conform
