#include "conform/pipelines/saddle/saddle_json.h"

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {
namespace {

// deg / 180 first, so that 90 deg is exactly pi / 2 (the paper's joint) and 45 deg exactly pi / 4.

}  // namespace

SaddleJobOptions saddle_job_options(const SaddleRequest& request) {
  SaddleJobOptions options;
  SaddleGeometry& geometry = options.saddle.geometry;
  geometry.leg_radius_mm = request.leg_radius_mm;
  geometry.pipe_radius_mm = request.pipe_radius_mm;
  geometry.pitch_rad = radians(request.pitch_deg);
  geometry.offset_mm = request.offset_mm;
  options.saddle.start_pose_rad = radians(request.right_angle_pose_deg);
  if (request.step_deg) {
    options.saddle.rule = SaddleStepRule::kEqualAngle;
    options.saddle.step_rad = radians(*request.step_deg);
  } else if (request.speed_mm_per_s && request.period_s) {
    options.saddle.rule = constant_speed_rule(geometry);
    options.saddle.speed_mm_per_s = *request.speed_mm_per_s;
    options.saddle.period_s = *request.period_s;
  } else {
    throw Error("saddle: give --step-deg A (equal-angle steps) or --speed MM_PER_S with --period S (constant speed)");
  }
  options.out_path = request.out_path;
  return options;
}

nlohmann::json saddle_json(const SaddleRequest& request, const SaddleJobResult& job) {
  const SaddleResult& s = job.saddle;
  const bool equal_angle = s.rule == SaddleStepRule::kEqualAngle;
  const auto given = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"points", s.points.size()},
          {"step_mm_min", s.step_mm_min},
          {"step_mm_max", s.step_mm_max},
          {"step_mm_mean", s.step_mm_mean},
          {"speed_ripple_pct", s.speed_ripple_pct},
          {"last_step_mm", s.last_step_mm},
          {"last_step_partial", s.last_step_partial},
          {"interpolation", to_string(s.rule)},
          {"converged", s.converged},
          {"curve_length_mm", s.curve_length_mm},
          {"path_length_mm", s.path_length_mm},
          {"pose_deg_min", degrees(s.pose_rad_min)},
          {"pose_deg_max", degrees(s.pose_rad_max)},
          {"max_pipe_residual_mm", s.max_pipe_residual_mm},
          {"max_cylinder_residual_mm", s.max_leg_residual_mm},
          {"R_mm", request.leg_radius_mm},
          {"r_mm", request.pipe_radius_mm},
          {"pitch_deg", request.pitch_deg},
          {"offset_mm", request.offset_mm},
          {"right_angle_pose_deg", request.right_angle_pose_deg},
          {"start_pose_deg", request.right_angle_pose_deg},  // the same value, under its old name
          {"corner_steps", s.corner_steps},
          {"step_deg", equal_angle ? given(request.step_deg) : nlohmann::json(nullptr)},
          {"speed_mm_per_s", equal_angle ? nlohmann::json(nullptr) : given(request.speed_mm_per_s)},
          {"period_s", equal_angle ? nlohmann::json(nullptr) : given(request.period_s)},
          {"out", json_path_or_null(job.out_path)}};
}

}  // namespace conform
