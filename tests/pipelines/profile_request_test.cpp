// `conform profile` as the CLI and Python take it: the request's defaults are the job's, and each conflicting or
// unknown choice is refused naming its flag.

#include "conform/pipelines/profile/profile_json.h"

#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

std::string error_of(const ProfileRequest& request) {
  try {
    profile_job_options(request);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ProfileRequest, DefaultsAreTheJobsDefaults) {
  ProfileRequest request;
  request.edge_path = "edge.csv";
  request.features_path = "features.csv";
  const ProfileJobOptions options = profile_job_options(request);
  const ProfileCompensationOptions defaults;
  EXPECT_EQ(options.edge_path, "edge.csv");
  EXPECT_EQ(options.features_path, "features.csv");
  EXPECT_EQ(options.compensation.edge.model, defaults.edge.model);
  EXPECT_EQ(options.compensation.edge.knot_spacing_mm, defaults.edge.knot_spacing_mm);
  EXPECT_EQ(options.compensation.edge.outlier_threshold_sigma, defaults.edge.outlier_threshold_sigma);
  EXPECT_EQ(options.compensation.edge.points.max_gap_mm, defaults.edge.points.max_gap_mm);
  EXPECT_EQ(options.compensation.edge.noise_mm, defaults.edge.noise_mm);
  EXPECT_EQ(options.compensation.sampling.chord_tolerance_mm, defaults.sampling.chord_tolerance_mm);
  EXPECT_EQ(options.compensation.web_width_mm, defaults.web_width_mm);
  EXPECT_FALSE(options.compensation.web_normal.has_value());
  EXPECT_FALSE(options.compensation.fit_web_plane);
  EXPECT_FALSE(options.compensation.reversed);
}

TEST(ProfileRequest, MapsEveryChoice) {
  ProfileRequest request;
  request.model = "spline";
  request.direction = "reverse";
  request.web_normal = Eigen::Vector3d(0.0, 0.0, 2.0);  // +z at any length: the paper's machine z, left unset
  ProfileJobOptions options = profile_job_options(request);
  EXPECT_EQ(options.compensation.edge.model, ProfileEdgeModel::kSpline);
  EXPECT_TRUE(options.compensation.reversed);
  EXPECT_FALSE(options.compensation.web_normal.has_value());
  request.web_normal = Eigen::Vector3d(0.0, 0.1, 1.0);
  options = profile_job_options(request);
  ASSERT_TRUE(options.compensation.web_normal.has_value());
  EXPECT_EQ(*options.compensation.web_normal, Eigen::Vector3d(0.0, 0.1, 1.0));
}

TEST(ProfileRequest, RefusesConflictsNamingTheFlag) {
  ProfileRequest request;
  request.model = "quintic";
  EXPECT_NE(error_of(request).find("--model: quintic"), std::string::npos);
  request = ProfileRequest{};
  request.direction = "up";
  EXPECT_NE(error_of(request).find("--direction: up"), std::string::npos);
  request = ProfileRequest{};
  request.web_plane = true;
  request.second_edge_path = "other.csv";
  EXPECT_NE(error_of(request).find("--web-plane excludes --second-edge"), std::string::npos);
  request = ProfileRequest{};
  request.web_normal = Eigen::Vector3d(0.0, 0.0, 1.0);
  request.web_plane = true;
  EXPECT_NE(error_of(request).find("--web-normal excludes"), std::string::npos);
  request = ProfileRequest{};
  request.web_normal = Eigen::Vector3d::Zero();
  EXPECT_NE(error_of(request).find("must be finite and not zero"), std::string::npos);
}

}  // namespace
}  // namespace conform
