// The smoothing cubic B-spline, closed and open: a noisy circle smoothed to within a third of the noise, C2 across
// the seam of a closed curve, exact reproduction of a cubic, derivatives, the smoothing target, and clear errors.

#include "conform/fitting/bspline_fit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

// The test's own deterministic Gaussian draws (Box-Muller on a 64-bit LCG).
class Noise {
 public:
  explicit Noise(std::uint64_t seed) : state_(seed) {}
  double uniform() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return (static_cast<double>(state_ >> 11) + 0.5) / 9007199254740992.0;
  }
  double normal() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * kPi * uniform()); }

 private:
  std::uint64_t state_;
};

struct Circle {
  Eigen::Vector3d centre{250.0, -80.0, 40.0};
  Eigen::Matrix3d frame = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
  double radius = 100.0;
  Eigen::Vector3d at(double theta) const {
    return centre + radius * (std::cos(theta) * frame.col(0) + std::sin(theta) * frame.col(1));
  }
  // Distance from the circle's centre in its plane, and the height off the plane.
  double radial(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = frame.transpose() * (p - centre);
    return q.head<2>().norm();
  }
};

// n points once round the circle at jittered angles, with isotropic Gaussian noise sigma per coordinate.
std::vector<Eigen::Vector3d> noisy_circle(const Circle& circle, int n, double sigma, std::uint64_t seed) {
  Noise noise(seed);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double theta = 2.0 * kPi * (i + 0.3 * noise.uniform()) / n;
    points.push_back(circle.at(theta) + sigma * Eigen::Vector3d(noise.normal(), noise.normal(), noise.normal()));
  }
  return points;
}

TEST(BSplineCurve, NoisyCircleSmoothedWithinAThirdOfTheNoise) {
  const Circle circle;
  const double sigma = 1.0;
  const int n = 2000;
  const std::vector<Eigen::Vector3d> points = noisy_circle(circle, n, sigma, 17);
  BSplineFitOptions options;
  options.closed = true;
  options.smoothing_mm2 = 3.0 * n * sigma * sigma;  // splprep's s for 3D noise of sigma per coordinate
  const BSplineFit fit = fit_bspline_curve(points, options);
  ASSERT_TRUE(fit.converged) << fit.termination;
  // The curve's distance from the circle, sampled densely round the whole period.
  double sum_squares = 0.0, mean = 0.0, worst = 0.0;
  constexpr int kSamples = 20000;
  for (int k = 0; k < kSamples; ++k) {
    const double u = fit.curve.u_begin() + (fit.curve.u_end() - fit.curve.u_begin()) * k / kSamples;
    const Eigen::Vector3d p = fit.curve.position(u);
    const Eigen::Vector3d q = circle.frame.transpose() * (p - circle.centre);
    const double error = std::hypot(circle.radial(p) - circle.radius, q.z());
    sum_squares += error * error;
    mean += (circle.radial(p) - circle.radius) / kSamples;
    worst = std::max(worst, error);
  }
  const double rms = std::sqrt(sum_squares / kSamples);
  std::printf(
      "[figures] closed B-spline, noisy circle R 100 mm, sigma %.1f mm, %d points: radius error rms %.4f mm "
      "(%.3f sigma), mean %.4f mm, max %.4f mm; lambda %.3g after %d solves, %zu control points\n",
      sigma, n, rms, rms / sigma, mean, worst, fit.lambda, fit.lambda_iterations, fit.curve.control_points().size());
  EXPECT_LT(rms, sigma / 3.0);
  EXPECT_LT(std::abs(mean), sigma / 3.0);
  EXPECT_NEAR(fit.weighted_ss_mm2, options.smoothing_mm2, 1e-5 * options.smoothing_mm2);
  EXPECT_NEAR(fit.curve.length(), 2.0 * kPi * circle.radius, 0.01 * 2.0 * kPi * circle.radius);
}

TEST(BSplineCurve, ClosedCurveIsC2AcrossTheSeam) {
  const Circle circle;
  BSplineFitOptions options;
  options.closed = true;
  options.control_points = 40;
  options.lambda = 1e-9;
  const BSplineFit fit = fit_bspline_curve(noisy_circle(circle, 300, 0.5, 23), options);
  ASSERT_TRUE(fit.ok);
  const double u0 = fit.curve.u_begin(), u1 = fit.curve.u_end();
  const double h = fit.curve.knot_spacing();
  // One-sided limits at the seam, delta from either side: a jump in order k would stay O(1) as delta shrinks; a
  // continuous derivative differs by about |S^(k+1)| 2 delta.
  for (double delta : {1e-4 * h, 1e-6 * h}) {
    for (int order = 0; order <= 2; ++order) {
      const Eigen::Vector3d before = fit.curve.derivative(u1 - delta, order);
      const Eigen::Vector3d after = fit.curve.derivative(u0 + delta, order);
      const double bound = 4.0 * delta *
                               std::max(fit.curve.derivative(u0 + delta, order + 1).norm(),
                                        fit.curve.derivative(u1 - delta, order + 1).norm()) +
                           1e-12 * std::max(1.0, before.norm());
      EXPECT_LE((before - after).norm(), bound) << "order " << order << ", delta " << delta;
    }
  }
  // The same at an inner knot, and the check can fail: the third derivative does jump there.
  const double knot = u0 + 17.0 * h;
  EXPECT_LE((fit.curve.derivative(knot - 1e-9 * h, 2) - fit.curve.derivative(knot + 1e-9 * h, 2)).norm(),
            1e-6 * fit.curve.derivative(knot, 2).norm());
  EXPECT_GT((fit.curve.derivative(knot - 1e-9 * h, 3) - fit.curve.derivative(knot + 1e-9 * h, 3)).norm(), 1e-9);
  // A parameter a period away is the same point.
  EXPECT_LE((fit.curve.position(u0 + 0.3 * h) - fit.curve.position(u1 + 0.3 * h)).norm(), 1e-9);
  EXPECT_LE((fit.curve.position(u0 + 0.3 * h) - fit.curve.position(u0 - (u1 - u0) + 0.3 * h)).norm(), 1e-9);
}

TEST(BSplineCurve, OpenCurveReproducesACubicAndItsDerivatives) {
  // Uniform cubic B-splines contain every cubic: without smoothing the fit is the cubic itself.
  const auto cubic = [](double u) {
    return Eigen::Vector3d(3.0 + u * (2.0 - 0.5 * u + 0.01 * u * u), -u * u * 0.2 + 0.003 * u * u * u, 7.0 * u);
  };
  std::vector<Eigen::Vector3d> points;
  std::vector<double> u;
  for (int i = 0; i <= 80; ++i) {
    u.push_back(10.0 * std::pow(i / 80.0, 1.3));
    points.push_back(cubic(u.back()));
  }
  BSplineFitOptions options;
  options.parameters = u;
  options.control_points = 12;
  const BSplineFit fit = fit_bspline_curve(points, options);
  ASSERT_TRUE(fit.ok);
  EXPECT_LE(fit.max_residual_mm, 1e-9);
  const double step = 1e-4;
  for (double s : {0.0, 1.1, 5.5, 9.99, 10.0}) {
    EXPECT_LE((fit.curve.position(s) - cubic(s)).norm(), 1e-9) << s;
    const Eigen::Vector3d numeric = (cubic(s + step) - cubic(s - step)) / (2.0 * step);
    EXPECT_LE((fit.curve.derivative(s, 1) - numeric).norm(), 1e-6) << s;
    const Eigen::Vector3d second = (cubic(s + step) - 2.0 * cubic(s) + cubic(s - step)) / (step * step);
    EXPECT_LE((fit.curve.derivative(s, 2) - second).norm(), 1e-5) << s;
  }
}

TEST(BSplineCurve, SmoothingGrowsWithLambda) {
  const std::vector<Eigen::Vector3d> points = noisy_circle(Circle{}, 400, 0.5, 31);
  double previous = -1.0;
  for (double lambda : {0.0, 1e-10, 1e-8, 1e-6, 1e-4}) {
    BSplineFitOptions options;
    options.closed = true;
    options.lambda = lambda;
    const BSplineFit fit = fit_bspline_curve(points, options);
    ASSERT_TRUE(fit.ok) << lambda;
    EXPECT_GT(fit.weighted_ss_mm2, previous) << lambda;
    previous = fit.weighted_ss_mm2;
  }
}

TEST(BSplineCurve, EffectiveDegreesOfFreedomRunFromTheControlPointsToALine) {
  // The smoother's trace: m with no smoothing (every control point free), 2 when the bending weight forces a line
  // (Hastie & Tibshirani 3.5), and in between it falls as lambda grows.
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 200; ++i) points.emplace_back(i, std::sin(0.05 * i), 0.0);
  double previous = 1e9;
  for (double lambda : {0.0, 1e-6, 1e-3, 1e3}) {
    BSplineFitOptions options;
    options.control_points = 20;
    options.lambda = lambda;
    options.effective_dof = true;
    const BSplineFit fit = fit_bspline_curve(points, options);
    if (lambda == 0.0) {
      EXPECT_NEAR(fit.effective_dof, 20.0, 1e-6);
    }
    if (lambda == 1e3) {
      EXPECT_NEAR(fit.effective_dof, 2.0, 0.01);
    }
    EXPECT_LT(fit.effective_dof, previous + 1e-9) << lambda;
    previous = fit.effective_dof;
  }
  BSplineFitOptions without;
  without.control_points = 20;
  EXPECT_EQ(fit_bspline_curve(points, without).effective_dof, 0.0);
}

TEST(BSplineCurve, ClosedWithGivenParameters) {
  // Parameters one per point plus the period's end; the last point need not repeat the first.
  const Circle circle;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> u;
  for (int i = 0; i < 64; ++i) {
    u.push_back(2.0 * kPi * i / 64.0);
    points.push_back(circle.at(u.back()));
  }
  u.push_back(2.0 * kPi);
  BSplineFitOptions options;
  options.closed = true;
  options.parameters = u;
  options.control_points = 32;
  const BSplineFit fit = fit_bspline_curve(points, options);
  ASSERT_TRUE(fit.ok);
  EXPECT_DOUBLE_EQ(fit.curve.u_end(), 2.0 * kPi);
  EXPECT_LE(fit.max_residual_mm, 1e-3);                                   // a cubic spline through a circle, 32 spans
  EXPECT_NEAR(fit.curve.derivative(1.0, 1).norm(), circle.radius, 0.01);  // |dS/dtheta| = R
}

std::string error_of(const std::vector<Eigen::Vector3d>& points, const BSplineFitOptions& options) {
  try {
    fit_bspline_curve(points, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(BSplineCurve, DegenerateInputGivesAClearError) {
  const BSplineFitOptions open;
  const std::vector<Eigen::Vector3d> three = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}};
  EXPECT_NE(error_of(three, open).find("at least 4"), std::string::npos) << error_of(three, open);
  const std::vector<Eigen::Vector3d> same(10, Eigen::Vector3d(1, 2, 3));
  EXPECT_NE(error_of(same, open).find("coincide"), std::string::npos) << error_of(same, open);
  std::vector<Eigen::Vector3d> nan = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0}, {4, NAN, 0}};
  EXPECT_NE(error_of(nan, open).find("point 4 is not finite"), std::string::npos);
  // More control points than points, no smoothing: singular, and said so.
  std::vector<Eigen::Vector3d> six;
  for (int i = 0; i < 6; ++i) six.emplace_back(i, i * i, 0.0);
  BSplineFitOptions many;
  many.control_points = 20;
  EXPECT_NE(error_of(six, many).find("singular"), std::string::npos) << error_of(six, many);
  many.lambda = 1e-6;  // the bending energy makes it determined
  EXPECT_EQ(error_of(six, many), "no error");
  BSplineFitOptions bad_count;
  bad_count.closed = true;
  bad_count.parameters = {0, 1, 2, 3, 4, 5};  // closed needs 7 for 6 points
  EXPECT_NE(error_of(six, bad_count).find("need 7"), std::string::npos) << error_of(six, bad_count);
  BSplineFitOptions decreasing;
  decreasing.parameters = {0, 1, 3, 2, 4, 5};
  EXPECT_NE(error_of(six, decreasing).find("parameter 3 decreases"), std::string::npos);
}

}  // namespace
}  // namespace conform
