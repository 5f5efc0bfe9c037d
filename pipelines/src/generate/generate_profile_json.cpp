#include "conform/pipelines/generate/generate_profile_json.h"

#include <cmath>

#include "conform/core/constants.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {
namespace {

// deg / 180 first, so that 90 deg is exactly pi / 2.

}  // namespace

GenerateProfileOptions generate_profile_options(const GenerateProfileRequest& request) {
  GenerateProfileOptions options;
  options.scan = request.scan;
  options.scan.deformation.twist_rad = radians(request.twist_deg);
  options.scan.deformation.kink_rad = radians(request.kink_deg);
  options.scan.offset_mm = request.offset_mm;
  options.out_path = request.out_path;
  return options;
}

nlohmann::json generate_profile_json(const GenerateProfileResult& r) {
  nlohmann::json j = r.truth;
  j["edge_path"] = r.edge_path;
  j["second_edge_path"] = json_path_or_null(r.second_edge_path);
  j["features_path"] = r.features_path;
  j["truth_path"] = r.truth_path;
  j["truth_json_path"] = r.truth_json_path;
  j["features"] = r.features;
  return j;
}

}  // namespace conform
