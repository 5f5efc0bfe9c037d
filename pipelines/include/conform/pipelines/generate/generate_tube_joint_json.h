#pragma once
// `conform generate tube-joint` as the CLI and the Python binding (conform.generate_tube_joint) take it, in the CLI's
// units (degrees and percent as given, bumps as numbers), its conversion to the job's Options, and its JSON: one
// source for both.

#include <array>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "conform/pipelines/generate/generate_tube_joint.h"

namespace conform {

struct GenerateTubeJointRequest {
  GenerateTubeJointRequest() { job.joint.leg.radius_mm = 1000.0; }

  // Paths, offset, protrusion (0: automatic), radii, wall, vertex counts, stub length (0: automatic), truth points.
  GenerateTubeJointOptions job;
  double pitch_deg = 90.0;
  double edge_mm = 5.0;  // both scans' mesh edge
  double ovality_pct = 0.0;  // D_max - D_min in % of D, both tubes
  double peaking_mm = 0.0;   // at both seam welds, radial
  double leg_seam_deg = 15.0;
  double stub_seam_deg = 100.0;
  double seam_width_mm = 150.0;
  double noise_mm = 0.0;
  double leg_arc_deg = 0.0;                      // 0: a patch around the joint
  std::vector<std::array<double, 4>> leg_bumps;  // AZ_DEG, Z_L_MM, HEIGHT_MM, RADIUS_MM
  std::vector<std::array<double, 4>> stub_bumps;  // AZ_DEG, Z_S_MM, HEIGHT_MM, RADIUS_MM
  std::uint64_t seed = 1;                          // leg: seed, stub: seed + 1
  bool ascii = false;
};

GenerateTubeJointOptions generate_tube_joint_options(const GenerateTubeJointRequest& request);

nlohmann::json generate_tube_joint_json(const GenerateTubeJointOptions& options,
                                        const GenerateTubeJointResult& result);

}  // namespace conform
