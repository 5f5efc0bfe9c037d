#pragma once
// `conform tube-joint` as the CLI and the Python binding (conform.tube_joint) take it, in the CLI's units (degrees as
// given), its conversion to the job's Options, and its JSON: one source for both.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "conform/pipelines/tube_joint/tube_joint.h"

namespace conform {

struct TubeJointRequest {
  TubeJointJobOptions job;                          // paths, offset, protrusion, markers, solve options in mm
  std::optional<double> pitch_deg;                  // --pitch-deg; required unless job.leg_pose_path
  bool protrusion_given = false;                    // --protrusion; required unless job.leg_pose_path
  double step_deg = 1.0;                            // --step-deg: equal azimuth steps, unless step_mm
  std::optional<double> step_mm;                    // --step-mm: equal arc-length steps
  double smoothing_mm2 = -1.0;                      // --smoothing
  double smoothing_rms_mm = 0.0;                    // --smoothing-rms
  std::optional<std::array<double, 4>> groove_deg;  // --groove-deg toe, side, heel, side
  std::string groove_table_path;                    // --groove-table CSV phi_deg,alpha_deg
  std::string interpolation = "linear";             // --groove-interpolation: linear, quadratic, spline
  std::vector<double> walls_mm;                     // --wall-thickness: none, one for both, or leg, stub
  double weld_angle_deg = 45.0;                     // --weld-angle-deg
};

// Throws conform::Error with the CLI's message for a missing pitch or protrusion, a bad groove table file, a wall
// thickness that is not > 0 or an unknown interpolation.
TubeJointJobOptions tube_joint_job_options(const TubeJointRequest& request);

nlohmann::json tube_joint_json(const TubeJointJobResult& job);

}  // namespace conform
