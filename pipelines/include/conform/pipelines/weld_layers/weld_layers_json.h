#pragma once
// The JSON of `conform weld-layers --json`, one source for the CLI and the Python binding (conform.weld_layers).

#include <nlohmann/json.hpp>

#include "conform/pipelines/weld_layers/weld_layers.h"

namespace conform {

const char* to_string(BiasMode mode);  // "check", "remove", "keep": the CLI's --bias values

// An empty options.reference_path is reported as the Coons patch of the eroded border (--reference-from-border).
nlohmann::json weld_layers_json(const WeldLayersJobOptions& options, const WeldLayersJobResult& job);

}  // namespace conform
