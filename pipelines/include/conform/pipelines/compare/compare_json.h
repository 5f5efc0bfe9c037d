#pragma once
// The JSON of `conform compare --json`, one source for the CLI and the Python binding (conform.compare).

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/compare/compare.h"

namespace conform {

// scan_units, reference_units: the unit names the inputs were given in ("mm", "m", ...), echoed as the JSON's
// "scan_units" and "reference_units", and as "units" when they agree (null when they do not).
nlohmann::json compare_json(const CompareOptions& options, const CompareResult& result, const std::string& scan_units,
                            const std::string& reference_units);

}  // namespace conform
