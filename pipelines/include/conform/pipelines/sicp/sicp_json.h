#pragma once
// The JSON of `conform sicp --json`, and the text forms of --model, --projection-fit and --normals: one source for
// the CLI and the Python binding (conform.sicp).

#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/sicp/sicp.h"

namespace conform {

nlohmann::json sicp_json(const SicpJobResult& result);

// model: "sicp", "rigid" or "projection"; fit: "parabola" or "spline"; normals: "rotate" or "scan". Throws
// conform::Error for anything else, naming the flag.
void set_sicp_choices(const std::string& model, const std::string& fit, const std::string& normals,
                      SicpCompensationOptions* options);

}  // namespace conform
