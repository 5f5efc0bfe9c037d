#include "conform/compensation/profile_edge_points.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {
namespace {

// A gently bowed edge along +x, a point every `spacing` mm, with gaussian noise sigma.
std::vector<Eigen::Vector3d> bowed_edge(int n, double spacing, double sigma, std::uint64_t seed = 3) {
  Random random(seed);
  std::vector<Eigen::Vector3d> points;
  const double length = (n - 1) * spacing;
  for (int i = 0; i < n; ++i) {
    const double x = i * spacing, u = x / length;
    points.emplace_back(x + sigma * random.normal(), 40.0 * 4.0 * u * (1.0 - u) + sigma * random.normal(),
                        sigma * random.normal());
  }
  return points;
}

std::string message_of(const std::vector<Eigen::Vector3d>& points, const ProfileEdgePointsOptions& options = {}) {
  try {
    check_profile_edge_points(points, options, "edge.csv");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ProfileEdgePoints, DescribesAGoodEdge) {
  const ProfileEdgePointsCheck check = check_profile_edge_points(bowed_edge(401, 5.0, 0.0), {}, "edge.csv");
  EXPECT_NEAR(check.median_spacing_mm, 5.0, 0.01);  // a 40 mm bow over 2 m (slope <= 0.08) lengthens a step < 0.016 mm
  EXPECT_NEAR(check.axis.x(), 1.0, 1e-3);
  EXPECT_GT(check.chord_length_mm, 2000.0);
  EXPECT_LT(check.chord_length_mm, 2000.0 + 3.0);  // the arc of a 40 mm bow over 2 m is ~2 mm longer than its chord
}

TEST(ProfileEdgePoints, EstimatesTheNoise) {
  // 4,000 triples: the median's relative standard error is a few per cent.
  EXPECT_NEAR(estimate_edge_noise_mm(bowed_edge(4001, 5.0, 0.1)), 0.1, 0.008);
  EXPECT_NEAR(estimate_edge_noise_mm(bowed_edge(4001, 5.0, 0.5)), 0.5, 0.04);
  EXPECT_LT(estimate_edge_noise_mm(bowed_edge(4001, 5.0, 0.0)), 1e-4);  // only the bow's curvature, 5e-5 mm
}

TEST(ProfileEdgePoints, RefusesPointsOutOfOrderNamingThem) {
  std::vector<Eigen::Vector3d> points = bowed_edge(50, 5.0, 0.0);
  std::swap(points[17], points[18]);
  const std::string message = message_of(points);
  EXPECT_NE(message.find("edge.csv: point 18 (85.000"), std::string::npos) << message;
  EXPECT_NE(message.find("not in measuring order"), std::string::npos) << message;
}

TEST(ProfileEdgePoints, RefusesAGapNamingIt) {
  std::vector<Eigen::Vector3d> points = bowed_edge(50, 5.0, 0.0);
  points.erase(points.begin() + 20, points.begin() + 32);  // 13 steps of 5 mm: a 65 mm gap
  ProfileEdgePointsOptions options;
  options.max_gap_mm = 50.0;
  const std::string message = message_of(points, options);
  EXPECT_NE(message.find("point 20 (160.000"), std::string::npos) << message;
  EXPECT_NE(message.find("a gap larger than 50 mm"), std::string::npos) << message;
  options.max_gap_mm = 70.0;
  EXPECT_EQ(message_of(points, options), "");
}

TEST(ProfileEdgePoints, RefusesTooFewAndNonFinitePoints) {
  EXPECT_NE(message_of(bowed_edge(3, 5.0, 0.0)).find("3 edge points; at least 4"), std::string::npos);
  std::vector<Eigen::Vector3d> points = bowed_edge(10, 5.0, 0.0);
  points[4].y() = NAN;
  EXPECT_NE(message_of(points).find("point 4"), std::string::npos);
  ProfileEdgePointsOptions bad;
  bad.max_gap_mm = 0.0;
  EXPECT_FALSE(bad.IsValid(nullptr));
  EXPECT_NE(message_of(bowed_edge(10, 5.0, 0.0), bad).find("max_gap_mm"), std::string::npos);
}

}  // namespace
}  // namespace conform
