#pragma once
// Eigen values as JSON: vectors as arrays, 4x4 transforms as four row arrays (row-major, like the files).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

namespace conform::app {

inline nlohmann::json to_json(const Eigen::Vector3d& v, bool null_if = false) {
  if (null_if) return nullptr;
  return nlohmann::json::array({v.x(), v.y(), v.z()});
}

inline nlohmann::json to_json(const Eigen::Isometry3d& T) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

}  // namespace conform::app
