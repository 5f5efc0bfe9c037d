#pragma once
// The JSON of `conform pose-error --json`, one source for the CLI and the Python binding (conform.pose_error).

#include <nlohmann/json.hpp>

#include "conform/pipelines/pose_error/pose_error.h"

namespace conform {

nlohmann::json pose_error_json(const PoseErrorOptions& options, const PoseErrorResult& result);

}  // namespace conform
