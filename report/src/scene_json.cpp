// The scene as the page's script reads it: positions as float32 relative to the scene's origin (subtracted in
// double first, so that coordinates far from 0 keep their sub-micrometre detail), colours as uint8 RGB, triangle
// indices as uint32, each a little-endian array in base64.

#include <cstdint>
#include <cstring>

#include <nlohmann/json.hpp>

#include "report_detail.h"

namespace conform::html::detail {
namespace {

void append_le32(std::string& out, std::uint32_t bits) {
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((bits >> shift) & 0xffu);
}

void append_float(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits = 0;
  std::memcpy(&bits, &f, sizeof bits);
  append_le32(out, bits);
}

std::string positions_base64(const std::vector<Eigen::Vector3d>& positions, const Eigen::Vector3d& origin) {
  std::string bytes;
  bytes.reserve(12 * positions.size());
  for (const Eigen::Vector3d& p : positions) {
    const Eigen::Vector3d local = p - origin;
    for (int k = 0; k < 3; ++k) append_float(bytes, local[k]);
  }
  return base64(bytes);
}

std::string directions_base64(const std::vector<Eigen::Vector3d>& directions) {
  std::string bytes;
  bytes.reserve(12 * directions.size());
  for (const Eigen::Vector3d& d : directions) {
    for (int k = 0; k < 3; ++k) append_float(bytes, d[k]);
  }
  return base64(bytes);
}

std::string values_base64(const std::vector<double>& values) {
  std::string bytes;
  bytes.reserve(4 * values.size());
  for (double v : values) append_float(bytes, v);
  return base64(bytes);
}

std::string colours_base64(const std::vector<Rgb>& colours) {
  std::string bytes;
  bytes.reserve(3 * colours.size());
  for (const Rgb& c : colours) bytes.append({static_cast<char>(c[0]), static_cast<char>(c[1]), static_cast<char>(c[2])});
  return base64(bytes);
}

std::string indices_base64(const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  std::string bytes;
  bytes.reserve(12 * triangles.size());
  for (const auto& t : triangles) {
    for (std::uint32_t v : t) append_le32(bytes, v);
  }
  return base64(bytes);
}

const char* kind_name(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kPoints: return "points";
    case ObjectKind::kMesh: return "mesh";
    case ObjectKind::kPolyline: return "polyline";
    case ObjectKind::kArrows: return "arrows";
  }
  return "points";
}

}  // namespace

std::string scene_json(const Scene& scene, const std::vector<SceneObject>& thinned) {
  const Eigen::Vector3d origin = scene.origin();
  nlohmann::json objects = nlohmann::json::array();
  for (const SceneObject& o : thinned) {
    nlohmann::json j = {{"name", o.name},
                        {"kind", kind_name(o.kind)},
                        {"visible", o.visible},
                        {"count", o.positions.size()},
                        {"positions", positions_base64(o.positions, origin)},
                        {"colour", {o.colour[0], o.colour[1], o.colour[2]}},
                        {"size_px", o.size_px},
                        {"opacity", o.opacity},
                        {"length", o.length_mm},
                        {"closed", o.closed},
                        {"pieces", o.pieces}};
    if (!o.colours.empty()) j["colours"] = colours_base64(o.colours);
    if (!o.triangles.empty()) {
      j["triangles"] = o.triangles.size();
      j["indices"] = indices_base64(o.triangles);
    }
    if (!o.directions.empty()) j["directions"] = directions_base64(o.directions);
    if (!o.values.empty()) {
      j["values"] = values_base64(o.values);
      j["value_label"] = o.value_label;
    }
    objects.push_back(std::move(j));
  }
  nlohmann::json callouts = nlohmann::json::array();
  for (const Callout& c : scene.callouts()) {
    const Eigen::Vector3d local = c.position - origin;
    callouts.push_back({{"at", {local.x(), local.y(), local.z()}}, {"label", c.label}});
  }
  nlohmann::json j = {{"origin", {origin.x(), origin.y(), origin.z()}},
                      {"objects", std::move(objects)},
                      {"callouts", std::move(callouts)}};
  return j.dump();
}

}  // namespace conform::html::detail
