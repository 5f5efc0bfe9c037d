#pragma once
// The JSON of `conform inspect --json`, one source for the CLI and the Python binding.

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/inspect/inspect.h"

namespace conform {

nlohmann::json inspect_json(const InspectOptions& options, const InspectResult& result, const std::string& units);
// One face's object of the `faces` array.
nlohmann::json face_json(const FaceInspection& face);
// One hole's or boss's object of the `features` array: its cylinder's figures as face_json gives them, with `kind`
// ("hole", "boss"), `faces` (its face ids), `nominal_diameter_mm` and, with --tolerances, `tolerance`.
nlohmann::json feature_json(const FeatureInspection& feature);
// How the best fit beside the datum frame was made, by InspectResult::alignment (the JSON's best_fit.pose).
const char* best_fit_pose_name(const std::string& alignment);

}  // namespace conform
