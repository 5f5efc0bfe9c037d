#pragma once
// `conform generate profile` as the CLI and the Python binding (conform.generate_profile) take it, in the CLI's
// units (degrees as given), its conversion to the job's Options, and its JSON: one source for both.

#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "conform/pipelines/generate/generate_profile.h"

namespace conform {

struct GenerateProfileRequest {
  ProfileScanOptions scan;  // lengths in mm as given; its twist_rad and kink_rad are set from the degrees below
  std::string out_path;
  double twist_deg = 0.0;
  double kink_deg = 0.0;
  Eigen::Vector3d offset_mm = Eigen::Vector3d::Zero();
};

GenerateProfileOptions generate_profile_options(const GenerateProfileRequest& request);

// The truth JSON with the files written and the number of features.
nlohmann::json generate_profile_json(const GenerateProfileResult& result);

}  // namespace conform
