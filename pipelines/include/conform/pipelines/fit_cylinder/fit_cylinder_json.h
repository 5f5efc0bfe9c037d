#pragma once
// The JSON of `conform fit-cylinder --json`, one source for the CLI and the Python binding (conform.fit_cylinder).

#include <nlohmann/json.hpp>

#include "conform/pipelines/fit_cylinder/fit_cylinder.h"

namespace conform {

nlohmann::json fit_cylinder_json(const FitCylinderJobResult& job);

}  // namespace conform
