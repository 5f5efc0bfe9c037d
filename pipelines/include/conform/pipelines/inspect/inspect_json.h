#pragma once
// The JSON of `conform inspect --json`, one source for the CLI and the Python binding.

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/inspect/inspect.h"

namespace conform {

nlohmann::json inspect_json(const InspectOptions& options, const InspectResult& result, const std::string& units);
// One face's object of the `faces` array.
nlohmann::json face_json(const FaceInspection& face);

}  // namespace conform
