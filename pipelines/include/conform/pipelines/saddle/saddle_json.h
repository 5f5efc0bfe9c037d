#pragma once
// `conform saddle` as the CLI and the Python binding (conform.saddle) take it, in the CLI's units (degrees as given,
// so that the JSON echoes them bit for bit), and its JSON: one source for both.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "conform/pipelines/saddle/saddle.h"

namespace conform {

struct SaddleRequest {
  double leg_radius_mm = 0.0;            // --R
  double pipe_radius_mm = 0.0;           // --r
  double pitch_deg = 90.0;               // --pitch-deg
  double offset_mm = 0.0;                // --offset
  double right_angle_pose_deg = 0.0;     // --right-angle-pose-deg
  std::optional<double> step_deg;        // equal-angle steps; or
  std::optional<double> speed_mm_per_s;  // constant speed, with
  std::optional<double> period_s;
  std::string out_path;
};

// Degrees to radians (deg / 180 first, so that 90 deg is exactly pi / 2) and the step rule. Throws conform::Error
// when neither a step nor a speed with a period is given.
SaddleJobOptions saddle_job_options(const SaddleRequest& request);

nlohmann::json saddle_json(const SaddleRequest& request, const SaddleJobResult& job);

}  // namespace conform
