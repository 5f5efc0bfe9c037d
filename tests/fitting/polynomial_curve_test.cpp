// The chord-length polynomial space curve: exact recovery of a cubic, a degree-11 fit of a helix segment whose arc
// length matches the closed form, t(s) inverting s(t), derivatives, residuals, and clear errors on degenerate input.

#include "conform/fitting/polynomial_curve.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

const std::vector<Eigen::Vector3d> kCubic = {
    {1200.0, -35.0, 410.0}, {850.0, 12.0, -3.0}, {-140.0, 60.0, 8.5}, {55.0, -20.0, -2.25}};

Eigen::Vector3d cubic(double t) { return kCubic[0] + t * (kCubic[1] + t * (kCubic[2] + t * kCubic[3])); }

// Points on the cubic at uneven parameters in [0, 1].
void cubic_points(std::vector<Eigen::Vector3d>* points, std::vector<double>* t) {
  for (int i = 0; i < 60; ++i) {
    const double x = i / 59.0;
    t->push_back(x * x * (1.5 - 0.5 * x));  // 0 .. 1, denser at the start
    points->push_back(cubic(t->back()));
  }
}

TEST(PolynomialCurve, RecoversAnExactCubic) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> t;
  cubic_points(&points, &t);
  const PolynomialCurveFit fit = fit_polynomial_curve(points, t, PolynomialCurveOptions{});
  ASSERT_TRUE(fit.ok) << fit.termination;
  const std::vector<Eigen::Vector3d> q = fit.curve.power_coefficients();
  ASSERT_EQ(q.size(), 4u);
  double worst = 0.0;
  for (int k = 0; k < 4; ++k)
    worst = std::max(worst, (q[static_cast<std::size_t>(k)] - kCubic[static_cast<std::size_t>(k)]).norm());
  std::printf("[figures] exact cubic: max coefficient error %.2e mm, max residual %.2e mm, condition %.1f\n", worst,
              fit.max_residual_mm, fit.condition_number);
  EXPECT_LE(worst, 1e-9);
  EXPECT_LE(fit.max_residual_mm, 1e-9);
  for (double s : {-0.2, 0.0, 0.37, 1.0, 1.3}) {  // also beyond [0, 1]: the same polynomial
    EXPECT_LE((fit.curve.position(s) - cubic(s)).norm(), 1e-9);
    const Eigen::Vector3d d1 = kCubic[1] + s * (2.0 * kCubic[2] + 3.0 * s * kCubic[3]);
    const Eigen::Vector3d d2 = 2.0 * kCubic[2] + 6.0 * s * kCubic[3];
    EXPECT_LE((fit.curve.derivative(s, 1) - d1).norm(), 1e-8);
    EXPECT_LE((fit.curve.derivative(s, 2) - d2).norm(), 1e-7);
    EXPECT_LE((fit.curve.derivative(s, 3) - 6.0 * kCubic[3]).norm(), 1e-7);
    EXPECT_EQ(fit.curve.derivative(s, 4), Eigen::Vector3d::Zero());
  }
}

TEST(PolynomialCurve, ChordLengthParametersOfALineAreItsCubic) {
  // Unevenly spaced points on a straight line: chord length is exactly the line's parameter, so the cubic is the line.
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3d a(10, 20, 30), b(-200, 55, 1000);
  for (double t : {0.0, 0.01, 0.1, 0.15, 0.4, 0.41, 0.8, 1.0}) points.push_back(a + t * (b - a));
  const PolynomialCurveFit fit = fit_polynomial_curve(points, PolynomialCurveOptions{});
  EXPECT_DOUBLE_EQ(fit.parameters.front(), 0.0);
  EXPECT_DOUBLE_EQ(fit.parameters.back(), 1.0);
  EXPECT_NEAR(fit.parameters[4], 0.4, 1e-15);
  const std::vector<Eigen::Vector3d> q = fit.curve.power_coefficients();
  EXPECT_LE((q[0] - a).norm(), 1e-9);
  EXPECT_LE((q[1] - (b - a)).norm(), 1e-9);
  EXPECT_LE(q[2].norm() + q[3].norm(), 1e-9);
  EXPECT_NEAR(fit.chord_length_mm, (b - a).norm(), 1e-9);
}

TEST(PolynomialCurve, HelixSegmentArcLengthMatchesTheClosedForm) {
  // A quarter turn of a helix (radius 400 mm, rise 120 mm per turn) sampled at equal angles: equal chords, so the
  // chord-length parameter is exactly proportional to the angle. Degree 11 approximates it to ~1e-13 of its size.
  const double a = 400.0, b = 120.0 / (2.0 * kPi), span = 0.5 * kPi;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 200; ++i) {
    const double theta = span * i / 200.0;
    points.emplace_back(a * std::cos(theta), a * std::sin(theta), b * theta);
  }
  PolynomialCurveOptions options;
  options.degree = 11;
  const PolynomialCurveFit fit = fit_polynomial_curve(points, options);
  ASSERT_TRUE(fit.ok);
  const double exact = std::hypot(a, b) * span;
  const double length = fit.curve.arc_length(0.0, 1.0);
  std::printf(
      "[figures] helix quarter turn, degree 11: arc length %.12f mm vs %.12f mm, relative error %.2e, "
      "max residual %.2e mm, condition %.1f\n",
      length, exact, std::abs(length / exact - 1.0), fit.max_residual_mm, fit.condition_number);
  EXPECT_NEAR(length / exact, 1.0, 1e-9);
  // Part of the segment: t = 0.3 .. 0.8 is the angle 0.3 span .. 0.8 span.
  EXPECT_NEAR(fit.curve.arc_length(0.3, 0.8) / (std::hypot(a, b) * 0.5 * span), 1.0, 1e-9);
}

TEST(PolynomialCurve, ParameterAtArcLengthInvertsArcLength) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> t;
  cubic_points(&points, &t);
  const PolynomialCurve curve = fit_polynomial_curve(points, t, PolynomialCurveOptions{}).curve;
  double worst = 0.0;
  for (double x : {0.0, 0.05, 0.33, 0.5, 0.9, 1.0}) {
    const ArcLengthInverse inverse = curve.parameter_at_arc_length(curve.arc_length(0.0, x));
    ASSERT_TRUE(inverse.converged);
    worst = std::max(worst, std::abs(inverse.t - x));
  }
  std::printf("[figures] cubic: max |t(s(t)) - t| %.2e\n", worst);
  EXPECT_LE(worst, 1e-12);
  // And s(t(s)) = s over another interval.
  const double s = 123.456;
  const ArcLengthInverse inverse = curve.parameter_at_arc_length(s, 0.2, 0.9);
  EXPECT_NEAR(curve.arc_length(0.2, inverse.t), s, 1e-9);
}

TEST(PolynomialCurve, ResidualsOfNoisyPoints) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> t;
  cubic_points(&points, &t);
  for (std::size_t i = 0; i < points.size(); ++i) points[i].z() += (i % 2 == 0 ? 0.5 : -0.5);
  const PolynomialCurveFit fit = fit_polynomial_curve(points, t, PolynomialCurveOptions{});
  ASSERT_EQ(fit.residual_mm.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    EXPECT_NEAR((points[i] - fit.curve.position(t[i])).norm(), fit.residual_mm[i], 1e-12);
    EXPECT_NEAR(fit.residuals[i].norm(), fit.residual_mm[i], 1e-12);
  }
  EXPECT_NEAR(fit.rms_mm, 0.5, 0.02);  // an alternating +-0.5 mm is not a cubic: it stays in the residuals
}

std::string error_of(const std::vector<Eigen::Vector3d>& points, int degree = 3) {
  PolynomialCurveOptions options;
  options.degree = degree;
  try {
    fit_polynomial_curve(points, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(PolynomialCurve, DegenerateInputGivesAClearError) {
  const std::vector<Eigen::Vector3d> three = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}};
  EXPECT_NE(error_of(three).find("3 points for a degree 3 curve"), std::string::npos) << error_of(three);
  const std::vector<Eigen::Vector3d> same(10, Eigen::Vector3d(1, 2, 3));
  EXPECT_NE(error_of(same).find("coincide"), std::string::npos) << error_of(same);
  // Ten points but only three distinct places: repeated points do not make a cubic determinable.
  std::vector<Eigen::Vector3d> repeated;
  for (int i = 0; i < 10; ++i) repeated.push_back(three[static_cast<std::size_t>(i * 3 / 10)]);
  EXPECT_NE(error_of(repeated).find("only 3 distinct"), std::string::npos) << error_of(repeated);
  std::vector<Eigen::Vector3d> nan = {{0, 0, 0}, {1, 0, 0}, {2, NAN, 0}, {3, 1, 0}, {4, 2, 0}};
  EXPECT_NE(error_of(nan).find("point 2 is not finite"), std::string::npos) << error_of(nan);
  EXPECT_NE(error_of(three, 0).find("degree must be in [1, 15]"), std::string::npos) << error_of(three, 0);
  // Collinear points are a valid curve (a line), not an error; the fit has no NaN.
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 12; ++i) line.emplace_back(i * 1.0, 2.0 * i, -i * 0.5);
  const PolynomialCurveFit fit = fit_polynomial_curve(line, PolynomialCurveOptions{});
  EXPECT_TRUE(fit.ok);
  EXPECT_LE(fit.max_residual_mm, 1e-9);
}

}  // namespace
}  // namespace conform
