#pragma once
// `conform profile` as the CLI and the Python binding (conform.profile) take it, and the JSON of
// `conform profile --json`: one source for both.

#include <optional>
#include <string>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "conform/pipelines/profile/profile.h"

namespace conform {

struct ProfileRequest {
  std::string edge_path;         // --edge, required
  std::string features_path;     // --features, required
  std::string second_edge_path;  // --second-edge
  std::string out_path;          // --out
  std::string model = "auto";    // --model: auto, cubic, spline
  std::optional<Eigen::Vector3d> web_normal;  // --web-normal, any length; empty: machine +z (the paper)
  bool web_plane = false;                     // --web-plane
  double web_width_mm = ProfileCompensationOptions{}.web_width_mm;                // --web-width
  std::string direction = "forward";                                              // --direction: forward, reverse
  double knot_spacing_mm = ProfileEdgeFitOptions{}.knot_spacing_mm;               // --knot-spacing
  double outlier_sigma = ProfileEdgeFitOptions{}.outlier_threshold_sigma;         // --outlier-sigma
  double chord_tolerance_mm = ProfileSampleOptions{}.chord_tolerance_mm;          // --chord-tolerance
  double max_gap_mm = ProfileEdgePointsOptions{}.max_gap_mm;                      // --max-gap
  double noise_mm = ProfileEdgeFitOptions{}.noise_mm;                             // --noise
};

// The job's options. Throws conform::Error naming the flag: an unknown model or direction, --web-normal with
// --web-plane or --second-edge, --web-plane with --second-edge, a zero web normal.
ProfileJobOptions profile_job_options(const ProfileRequest& request);

nlohmann::json profile_json(const ProfileJobOptions& options, const ProfileJobResult& job);

}  // namespace conform
