// fitting/revolved.h: least-squares cones and tori against generated points with known parameters and noise,
// from a start off the truth (as a scan's cone or torus is off its nominal), and the inputs that determine nothing.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/random.h"
#include "conform/fitting/revolved.h"

namespace conform {
namespace {

constexpr double kNoise = 0.005;

// Points on a cone (apex, unit axis, half-angle) between heights h0 and h1 from the apex over `turn` radians, each
// moved by Gaussian noise along the surface's normal.
std::vector<Eigen::Vector3d> cone_points(const Eigen::Vector3d& apex, const Eigen::Vector3d& axis, double alpha,
                                         double h0, double h1, double turn, std::uint64_t seed) {
  Random random(seed);
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < 4000; ++i) {
    const double h = random.uniform(h0, h1), t = random.uniform(0.0, turn);
    const Eigen::Vector3d radial = std::cos(t) * u + std::sin(t) * v;
    const Eigen::Vector3d normal = std::cos(alpha) * radial - std::sin(alpha) * axis;
    out.push_back(apex + h * axis + h * std::tan(alpha) * radial + kNoise * random.normal() * normal);
  }
  return out;
}

TEST(RevolvedFit, ConeFromANoisyPartialTurnIsItsApexAxisAndAngle) {
  const Eigen::Vector3d apex(5, -3, 12), axis = Eigen::Vector3d(0.1, 0.2, -1).normalized();
  const double alpha = 40.0 * M_PI / 180.0;
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const std::vector<Eigen::Vector3d> points = cone_points(apex, axis, alpha, 8.0, 14.0, 1.5 * M_PI, seed);
    // Start 0.2 mm, 1 deg and 1 deg off.
    const Eigen::Vector3d start_axis = Eigen::AngleAxisd(M_PI / 180.0, axis.unitOrthogonal()) * axis;
    const ConeFit fit = fit_cone(points, apex + Eigen::Vector3d(0.2, 0, 0), start_axis, alpha + M_PI / 180.0);
    ASSERT_TRUE(fit.ok) << seed;
    EXPECT_NEAR(fit.half_angle_rad, alpha, 0.01 * M_PI / 180.0);
    EXPECT_GT(fit.axis.dot(axis), std::cos(0.02 * M_PI / 180.0));
    EXPECT_LT((fit.apex - apex).norm(), 0.01);
    EXPECT_NEAR(fit.rms_mm, kNoise, 0.0005);
    // The distance is the orthogonal one: a point 0.3 mm off the surface along its normal reads 0.3.
    const Eigen::Vector3d u = axis.unitOrthogonal();
    const Eigen::Vector3d on = apex + 10.0 * axis + 10.0 * std::tan(alpha) * u;
    const Eigen::Vector3d normal = std::cos(alpha) * u - std::sin(alpha) * axis;
    EXPECT_NEAR(cone_distance(fit, on + 0.3 * normal), 0.3, 0.01);
  }
}

TEST(RevolvedFit, TorusFromANoisyPatchIsItsCentreAxisAndRadii) {
  const Eigen::Vector3d centre(-2, 4, 7), axis = Eigen::Vector3d(0.3, -0.1, 1).normalized();
  const double major = 10.0, minor = 3.0;
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  for (const std::uint64_t seed : {4u, 5u, 6u}) {
    Random random(seed);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 5000; ++i) {  // the outer half of the tube, three quarters round
      const double t = random.uniform(0.0, 1.5 * M_PI), s = random.uniform(-0.5 * M_PI, 0.5 * M_PI);
      const Eigen::Vector3d radial = std::cos(t) * u + std::sin(t) * v;
      const Eigen::Vector3d normal = std::cos(s) * radial + std::sin(s) * axis;
      points.push_back(centre + major * radial + (minor + kNoise * random.normal()) * normal);
    }
    const TorusFit fit = fit_torus(points, centre + Eigen::Vector3d(0.1, -0.1, 0.1), axis, major + 0.1, minor - 0.1);
    ASSERT_TRUE(fit.ok) << seed;
    EXPECT_LT((fit.centre - centre).norm(), 0.005);
    EXPECT_GT(fit.axis.dot(axis), std::cos(0.02 * M_PI / 180.0));
    EXPECT_NEAR(fit.major_radius_mm, major, 0.003);
    EXPECT_NEAR(fit.minor_radius_mm, minor, 0.003);
    EXPECT_NEAR(fit.rms_mm, kNoise, 0.0005);
    EXPECT_NEAR(torus_distance(fit, centre + (major + minor + 0.2) * u), 0.2, 0.005);
  }
}

TEST(RevolvedFit, PointsThatDetermineNothingAreRefused) {
  // Too few points.
  EXPECT_FALSE(fit_cone({{1, 0, 1}, {0, 1, 1}}, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.7).ok);
  EXPECT_FALSE(fit_torus({{1, 0, 1}}, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 10.0, 3.0).ok);
  // One circle of a cone (a single height, no noise): its angle and apex are not determined; nor from a bad start.
  std::vector<Eigen::Vector3d> ring;
  for (int i = 0; i < 100; ++i) {
    const double t = 2.0 * M_PI * i / 100.0;
    ring.emplace_back(5.0 * std::cos(t), 5.0 * std::sin(t), 10.0);
  }
  EXPECT_FALSE(fit_cone(ring, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.0).ok);
  EXPECT_FALSE(fit_cone(ring, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), std::atan(0.5)).ok);
  // The apex beyond the points (the start's cone opens away from them): no cone of that sense through them.
  EXPECT_FALSE(fit_cone(ring, Eigen::Vector3d(0, 0, 20), Eigen::Vector3d::UnitZ(), std::atan(0.5)).ok);
  // One circle of a torus (its outer equator, the start the truth): the two radii trade off, nothing fixes them.
  std::vector<Eigen::Vector3d> equator;
  for (int i = 0; i < 100; ++i) {
    const double t = 2.0 * M_PI * i / 100.0;
    equator.emplace_back(13.0 * std::cos(t), 13.0 * std::sin(t), 0.0);
  }
  EXPECT_FALSE(fit_torus(equator, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 10.0, 3.0).ok);
  // Radii that are no torus.
  EXPECT_FALSE(fit_torus(equator, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 10.0, 0.0).ok);
  EXPECT_FALSE(fit_torus(equator, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), -1.0, 3.0).ok);
  // A point that is no point, among a cone's that fit from the truth.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.1, 0.2, -1).normalized();
  std::vector<Eigen::Vector3d> cone = cone_points(Eigen::Vector3d(5, -3, 12), axis, 0.7, 8.0, 14.0, M_PI, 7);
  ASSERT_TRUE(fit_cone(cone, Eigen::Vector3d(5, -3, 12), axis, 0.7).ok);
  cone[3].x() = std::nan("");
  EXPECT_FALSE(fit_cone(cone, Eigen::Vector3d(5, -3, 12), axis, 0.7).ok);
}

}  // namespace
}  // namespace conform
