#include "conform/pipelines/generate/generate_eroded_json.h"

#include "conform/core/error.h"

namespace conform {

Crater eroded_crater(const std::vector<double>& v) {
  if (v.size() != 4 && v.size() != 5 && v.size() != 7) {
    throw Error("--crater: give X_MM,Y_MM,RADIUS_MM,DEPTH_MM[,INNER_RADIUS_MM[,LIP_MM,LIP_WIDTH_MM]] (4, 5 or 7 "
                "numbers)");
  }
  Crater c{v[0], v[1], v[2], v[3]};
  if (v.size() >= 5) c.inner_radius_mm = v[4];
  if (v.size() == 7) c.lip_mm = v[5], c.lip_width_mm = v[6];
  return c;
}

Bump eroded_bump(const std::vector<double>& v) {
  if (v.size() != 4) throw Error("--bump: give X_MM,Y_MM,RADIUS_MM,HEIGHT_MM (4 numbers)");
  return {v[0], v[1], v[2], v[3]};
}

nlohmann::json generate_eroded_json(const GenerateErodedOptions& options, const GenerateErodedResult& r) {
  return {{"eroded", r.eroded_path}, {"reference", r.reference_path}, {"rims", r.rims_path},
          {"rows", r.rows},          {"cols", r.cols},                {"craters", r.craters},
          {"max_depth_mm", r.max_depth_mm}, {"noise_mm", options.eroded.noise_mm}, {"seed", options.eroded.seed}};
}

}  // namespace conform
