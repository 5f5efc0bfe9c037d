#pragma once
// The JSON of `conform profile --json`, one source for the CLI and the Python binding (conform.profile).

#include <nlohmann/json.hpp>

#include "conform/pipelines/profile.h"

namespace conform {

nlohmann::json profile_json(const ProfileJobOptions& options, const ProfileJobResult& job);

}  // namespace conform
