#pragma once
// `conform generate eroded`: its crater and bump from the numbers the CLI's flags give, and its JSON: one source for
// the CLI and the Python binding (conform.generate_eroded).

#include <vector>

#include <nlohmann/json.hpp>

#include "conform/pipelines/generate/generate_eroded.h"

namespace conform {

// X_MM, Y_MM, RADIUS_MM, DEPTH_MM [, INNER_RADIUS_MM [, LIP_MM, LIP_WIDTH_MM]]: 4, 5 or 7 numbers; conform::Error
// naming --crater otherwise.
Crater eroded_crater(const std::vector<double>& values);
// X_MM, Y_MM, RADIUS_MM, HEIGHT_MM; conform::Error naming --bump otherwise.
Bump eroded_bump(const std::vector<double>& values);

nlohmann::json generate_eroded_json(const GenerateErodedOptions& options, const GenerateErodedResult& result);

}  // namespace conform
