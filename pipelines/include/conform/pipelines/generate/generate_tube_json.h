#pragma once
// `conform generate tube` as the CLI and the Python binding (conform.generate_tube) take it, in the CLI's units
// (degrees as given, vectors and lists parsed), its conversion to the job's Options, and its JSON: one source for both.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "conform/pipelines/generate/generate_tube.h"

namespace conform {

struct GenerateTubeRequest {
  TubeOptions tube;  // the lengths in mm as given (radius, length, edge or vertices, ovality, seam, bow, noise, ...)
  std::string out_path;
  double arc_deg = 360.0;
  double arc_center_deg = 0.0;
  bool inner = false;
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();
  std::optional<Eigen::Vector3d> azimuth_reference;  // empty: default_azimuth_reference(axis_direction)
  double ovality_azimuth_deg = 0.0;
  double seam_azimuth_deg = 0.0;
  double bow_azimuth_deg = 0.0;
  std::vector<std::array<double, 4>> bumps;  // AZ_DEG, Z_MM, HEIGHT_MM, RADIUS_MM
  std::vector<std::array<double, 3>> holes;  // AZ_DEG, Z_MM, RADIUS_MM
  std::string noise_type = "gaussian";       // or uniform
  std::string noise_direction = "normal";    // or isotropic
  std::uint64_t seed = 1;
  bool ascii = false;
  bool double_precision = false;
  bool normals = false;
};

// Throws conform::Error for an unknown noise type or direction.
GenerateTubeOptions generate_tube_options(const GenerateTubeRequest& request);

nlohmann::json generate_tube_json(const GenerateTubeResult& result);

}  // namespace conform
