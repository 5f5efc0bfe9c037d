#include "conform/compensation/profile_edge.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/datasets/random.h"

namespace conform {
namespace {

// The circular arc of radius R through angle a: C(t) = R (sin(a t), 1 - cos(a t), 0), length R a, known exactly.
std::vector<Eigen::Vector3d> arc_points(double R, double a, int n, double sigma = 0.0) {
  Random random(5);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double phi = a * i / (n - 1);
    points.emplace_back(R * std::sin(phi) + sigma * random.normal(),
                        R * (1.0 - std::cos(phi)) + sigma * random.normal(), sigma * random.normal());
  }
  return points;
}

TEST(ProfileEdge, ParsesModelNames) {
  ProfileEdgeModel m = ProfileEdgeModel::kAuto;
  EXPECT_TRUE(parse_profile_edge_model("spline", &m));
  EXPECT_EQ(m, ProfileEdgeModel::kSpline);
  EXPECT_TRUE(parse_profile_edge_model("cubic", &m));
  EXPECT_EQ(m, ProfileEdgeModel::kCubic);
  EXPECT_FALSE(parse_profile_edge_model("quintic", &m));
  EXPECT_STREQ(to_string(ProfileEdgeModel::kAuto), "auto");
}

TEST(ProfileEdge, ArcLengthInverseOfAKnownCubic) {
  // C(t) = (1000 t, 30 t^2, 10 t^3): its arc-length table and inverse against a direct quadrature.
  const PolynomialCurve cubic =
      PolynomialCurve::from_power_coefficients({Eigen::Vector3d::Zero(), Eigen::Vector3d(1000.0, 0.0, 0.0),
                                                Eigen::Vector3d(0.0, 30.0, 0.0), Eigen::Vector3d(0.0, 0.0, 10.0)});
  const ProfileEdgeCurve edge = ProfileEdgeCurve::cubic(cubic, 64);
  const double total = cubic.arc_length(0.0, 1.0);
  EXPECT_NEAR(edge.length_mm(), total, 1e-9);
  for (double s : {0.0, 1.0, 123.456, 500.0, 999.0, total}) {
    const ArcLengthInverse inverse = edge.parameter_at(s, 1e-9);
    EXPECT_TRUE(inverse.converged);
    // Solved to 1e-6 mm and beyond: checked against an independent quadrature from 0.
    EXPECT_NEAR(cubic.arc_length(0.0, inverse.t), s, 1e-8) << s;
    EXPECT_NEAR(edge.arc_length_at(inverse.t), s, 1e-8) << s;
  }
  EXPECT_THROW(edge.parameter_at(total + 0.01), Error);
  EXPECT_THROW(edge.parameter_at(-0.01), Error);
  EXPECT_NEAR(edge.approximate_parameter_at(0.5 * total), edge.parameter_at(0.5 * total).t, 0.01);
}

TEST(ProfileEdge, CubicFitOfAShallowArcHasTheArcsLength) {
  // R = 200 m through 3 degrees: 10.47 m long, a 68.5 mm sagitta; a cubic follows it to ~1e-3 mm.
  const double R = 200000.0, a = 3.0 * M_PI / 180.0;
  ProfileEdgeFitOptions options;
  options.model = ProfileEdgeModel::kCubic;
  const ProfileEdgeFit fit = fit_profile_edge(arc_points(R, a, 2001), options);
  EXPECT_EQ(fit.model, ProfileEdgeModel::kCubic);
  EXPECT_FALSE(fit.spline_fit.fitted);
  EXPECT_LT(fit.cubic_fit.max_mm, 0.01);
  EXPECT_NEAR(fit.curve.length_mm(), R * a, 0.01);
}

TEST(ProfileEdge, SplineFollowsAKinkTheCubicCannot) {
  // A straight edge that turns by 1 degree at x = 3000 (a corner): 6 m, a point every 5 mm, noise 0.05 mm.
  Random random(11);
  std::vector<Eigen::Vector3d> points;
  const double turn = 1.0 * M_PI / 180.0;
  for (int i = 0; i <= 1200; ++i) {
    const double s = 5.0 * i;
    Eigen::Vector3d p(s, 0.0, 0.0);
    if (s > 3000.0) p = Eigen::Vector3d(3000.0 + (s - 3000.0) * std::cos(turn), (s - 3000.0) * std::sin(turn), 0.0);
    points.push_back(p + 0.05 * Eigen::Vector3d(random.normal(), random.normal(), random.normal()));
  }
  ProfileEdgeFitOptions options;
  const ProfileEdgeFit fit = fit_profile_edge(points, options);
  EXPECT_EQ(fit.model, ProfileEdgeModel::kSpline) << fit.selection;
  EXPECT_GT(fit.cubic_fit.rms_mm, 1.0);   // the corner: millimetres
  EXPECT_LT(fit.spline_fit.rms_mm, 0.1);  // about sqrt(2) x 0.05 mm, plus the rounded corner
  EXPECT_NEAR(fit.noise_mm, 0.05, 0.005);
  EXPECT_NEAR(fit.curve.length_mm(), 6000.0, 0.1);  // the corner's rounding shortens it by less than 0.1 mm
  // A point 1 m after the corner lies where the corner put it.
  const Eigen::Vector3d p = fit.curve.position(fit.curve.parameter_at(4000.0).t);
  EXPECT_LT((p - Eigen::Vector3d(3000.0 + 1000.0 * std::cos(turn), 1000.0 * std::sin(turn), 0.0)).norm(), 0.1);
}

TEST(ProfileEdge, GivenNoiseSetsTheSmoothing) {
  ProfileEdgeFitOptions options;
  options.model = ProfileEdgeModel::kSpline;
  options.noise_mm = 0.2;
  const ProfileEdgeFit fit = fit_profile_edge(arc_points(200000.0, 0.01, 501, 0.2), options);
  EXPECT_EQ(fit.noise_mm, 0.2);
  // The smoothing target 2 n sigma^2 makes the RMS residual sqrt(2) sigma.
  EXPECT_NEAR(fit.spline_fit.rms_mm, std::sqrt(2.0) * 0.2, 0.01);
  options.noise_mm = -1.0;
  EXPECT_THROW(fit_profile_edge(arc_points(200000.0, 0.01, 501), options), Error);
}

}  // namespace
}  // namespace conform
