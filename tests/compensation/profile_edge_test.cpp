#include "conform/compensation/profile_edge.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/random.h"

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

// A bowed edge along +x: 40 mm at the middle of `length`, a point every `step`, noise sigma.
std::vector<Eigen::Vector3d> bowed(double length, double step, double sigma, std::uint64_t seed = 7) {
  Random random(seed);
  std::vector<Eigen::Vector3d> points;
  for (double x = 0.0; x <= length + 1e-9; x += step) {
    const double u = x / length;
    points.emplace_back(x + sigma * random.normal(), 40.0 * 4.0 * u * (1.0 - u) + sigma * random.normal(),
                        sigma * random.normal());
  }
  return points;
}

TEST(ProfileEdge, DuplicatesAreDroppedAndCounted) {
  std::vector<Eigen::Vector3d> points = bowed(3000.0, 5.0, 0.1);
  const ProfileEdgeFit clean = fit_profile_edge(points, {});
  for (std::size_t i : {10u, 200u, 201u}) {
    const Eigen::Vector3d repeat = points[i];
    points.insert(points.begin() + static_cast<std::ptrdiff_t>(i), repeat);
  }
  const ProfileEdgeFit fit = fit_profile_edge(points, {});
  EXPECT_EQ(fit.duplicates_dropped, 3u);
  EXPECT_EQ(fit.outliers, 0u);
  // The main axis is taken from every point, repeats included: it turns by ~1e-9 rad, the length moves by ~1e-5 mm.
  EXPECT_NEAR(fit.curve.length_mm(), clean.curve.length_mm(), 1e-3);
}

TEST(ProfileEdge, DenseNoisyScanIsAcceptedAndNotStretched) {
  // 0.24 mm steps with sigma 0.1: consecutive points often step back along the edge by noise. They are accepted,
  // and the length is not inflated (chord length adds ~2 sigma^2 / step per step: +300 mm over 1 m).
  const std::vector<Eigen::Vector3d> points = bowed(1000.0, 0.24, 0.1);
  const ProfileEdgeFit fit = fit_profile_edge(points, {});
  EXPECT_GT(fit.points.reordered, 50u);
  const double truth = 1000.0 + 8.0 / 3.0 * 40.0 * 40.0 / 1000.0;  // arc of the parabola, to 1e-4
  EXPECT_NEAR(fit.curve.length_mm(), truth, 0.5);  // the two end points' own noise along the edge
  EXPECT_GT(fit.points.chord_length_mm, truth + 5.0);  // what chord length would have said
  // A step back of 5 mm is no noise: refused, naming the tolerance.
  std::vector<Eigen::Vector3d> swapped = bowed(1000.0, 5.0, 0.05);
  std::swap(swapped[50], swapped[51]);
  try {
    fit_profile_edge(swapped, {}, "edge.csv");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("more than the noise allows"), std::string::npos) << e.what();
  }
}

TEST(ProfileEdge, OneSpikeIsRejectedAndDoesNotFlipAuto) {
  const std::vector<Eigen::Vector3d> clean = bowed(6000.0, 5.0, 0.1);
  const ProfileEdgeFit reference = fit_profile_edge(clean, {});
  for (double spike : {3.0, 30.0}) {
    std::vector<Eigen::Vector3d> points = clean;
    points[400].y() += spike;
    const ProfileEdgeFit fit = fit_profile_edge(points, {});
    EXPECT_EQ(fit.model, ProfileEdgeModel::kCubic) << spike << ": " << fit.selection;
    ASSERT_EQ(fit.outliers, 1u) << spike;
    EXPECT_EQ(fit.outlier_indices, std::vector<int>{400});
    // The curve is the one without the spike: the same within a thousandth of a millimetre near it.
    for (double s : {1900.0, 2000.0, 2100.0, 5000.0}) {
      const Eigen::Vector3d a = fit.curve.position(fit.curve.parameter_at(s).t);
      const Eigen::Vector3d b = reference.curve.position(reference.curve.parameter_at(s).t);
      EXPECT_LT((a - b).norm(), 0.01) << spike << " at " << s;
    }
  }
}

TEST(ProfileEdge, TooManyOutliersAreRefused) {
  std::vector<Eigen::Vector3d> points = bowed(3000.0, 5.0, 0.1);
  for (std::size_t i = 1; i + 1 < points.size(); i += 3) points[i].z() += 20.0;  // a third of the points
  try {
    fit_profile_edge(points, {}, "edge.csv");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("outliers"), std::string::npos) << e.what();
  }
}

TEST(ProfileEdge, FarFromTheOriginTheCurveIsTheSame) {
  // Shop coordinates 100 km away: the fit works in centred coordinates, so nothing but the offset changes.
  const std::vector<Eigen::Vector3d> points = bowed(3000.0, 5.0, 0.1);
  const Eigen::Vector3d offset(1e8, -2e8, 3e6);
  std::vector<Eigen::Vector3d> far = points;
  for (Eigen::Vector3d& p : far) p += offset;
  for (ProfileEdgeModel model : {ProfileEdgeModel::kCubic, ProfileEdgeModel::kSpline}) {
    ProfileEdgeFitOptions options;
    options.model = model;
    const ProfileEdgeFit here = fit_profile_edge(points, options), there = fit_profile_edge(far, options);
    EXPECT_NEAR(there.curve.length_mm(), here.curve.length_mm(), 1e-6);
    for (double s : {0.0, 1234.5, 2999.0}) {
      const Eigen::Vector3d a = there.curve.position(there.curve.parameter_at(s).t) - offset;
      EXPECT_LT((a - here.curve.position(here.curve.parameter_at(s).t)).norm(), 1e-6) << s;
    }
  }
}

TEST(ProfileEdge, KnotSpacingFollowsTheStepAndTheNoise) {
  ProfileEdgeFitOptions options;
  options.model = ProfileEdgeModel::kSpline;
  EXPECT_NEAR(fit_profile_edge(bowed(3000.0, 5.0, 0.1), options).knot_spacing_mm, 50.0, 0.1);   // 10 steps
  EXPECT_NEAR(fit_profile_edge(bowed(3000.0, 5.0, 0.5), options).knot_spacing_mm, 125.0, 8.0);  // 250 sigma
  EXPECT_NEAR(fit_profile_edge(bowed(3000.0, 1.0, 0.02), options).knot_spacing_mm, 20.0, 1e-9);  // the floor
}

}  // namespace
}  // namespace conform
