#pragma once
// The JSON of `conform compare --json`, one source for the CLI and the Python binding (conform.compare).

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/compare.h"

namespace conform {

// units: the unit name the inputs were given in ("mm", "m", ...), echoed as the JSON's "units".
nlohmann::json compare_json(const CompareOptions& options, const CompareResult& result, const std::string& units);

}  // namespace conform
