#pragma once
// Eigen values as JSON: the jobs' JSON helpers (pipelines/common/json_values.h) under the names the commands use.

#include "conform/pipelines/common/json_values.h"

namespace conform::app {

inline nlohmann::json to_json(const Eigen::Vector3d& v, bool null_if = false) { return json_of(v, null_if); }
inline nlohmann::json to_json(const Eigen::Isometry3d& T) { return json_of(T); }

}  // namespace conform::app
