#pragma once
// Values as a job's JSON writes them: vectors as arrays, 4x4 transforms as four row arrays (row-major, like the
// files), an empty path as null. Shared by the jobs' JSON (pipelines/*_json.h), which the CLI and the Python binding
// both print or return.

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

namespace conform {

inline nlohmann::json json_of(const Eigen::Vector3d& v, bool null_if = false) {
  if (null_if) return nullptr;
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

inline nlohmann::json json_of(const Eigen::Isometry3d& T) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

inline nlohmann::json json_path_or_null(const std::string& path) {
  return path.empty() ? nlohmann::json(nullptr) : nlohmann::json(path);
}

}  // namespace conform
