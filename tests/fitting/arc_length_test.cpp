// Adaptive Gauss-Legendre arc length and its safeguarded-Newton inverse against closed forms.

#include "conform/fitting/arc_length.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

// A helix of radius a and pitch 2 pi b travelled at a varying rate, theta(t) = 3 t + 2 sin t (theta' > 0): the speed
// sqrt(a^2 + b^2) theta'(t) is not constant, so the quadrature has work to do, and s(t) = sqrt(a^2 + b^2) theta(t).
struct Helix {
  double a = 40.0;
  double b = 7.5;
  double theta(double t) const { return 3.0 * t + 2.0 * std::sin(t); }
  double speed(double t) const { return std::hypot(a, b) * (3.0 + 2.0 * std::cos(t)); }
  double length(double t0, double t1) const { return std::hypot(a, b) * (theta(t1) - theta(t0)); }
};

TEST(ArcLength, HelixSegmentMatchesTheClosedForm) {
  const Helix helix;
  const SpeedFunction speed = [&](double t) { return helix.speed(t); };
  for (const auto& [t0, t1] : {std::pair{0.0, 1.0}, std::pair{-2.0, 5.5}, std::pair{0.3, 0.31}, std::pair{0.0, 40.0}}) {
    const ArcLengthIntegral integral = integrate_arc_length(speed, t0, t1);
    const double exact = helix.length(t0, t1);
    EXPECT_TRUE(integral.converged);
    EXPECT_NEAR(integral.length_mm / exact, 1.0, 1e-12) << t0 << " .. " << t1;
  }
  std::printf("[figures] helix segment t in [-2, 5.5]: relative error %.2e\n",
              std::abs(arc_length(speed, -2.0, 5.5) / helix.length(-2.0, 5.5) - 1.0));
  EXPECT_DOUBLE_EQ(arc_length(speed, 1.0, 0.0), -arc_length(speed, 0.0, 1.0));  // signed
  EXPECT_EQ(arc_length(speed, 2.0, 2.0), 0.0);
}

TEST(ArcLength, ParabolaMatchesTheClosedForm) {
  // C(t) = (t, t^2, 0): s(t) = t sqrt(1 + 4t^2) / 2 + asinh(2t) / 4.
  const SpeedFunction speed = [](double t) { return std::sqrt(1.0 + 4.0 * t * t); };
  const auto s = [](double t) { return 0.5 * t * std::sqrt(1.0 + 4.0 * t * t) + 0.25 * std::asinh(2.0 * t); };
  EXPECT_NEAR(arc_length(speed, -1.0, 3.0) / (s(3.0) - s(-1.0)), 1.0, 1e-12);
}

TEST(ArcLength, InverseInvertsTheLength) {
  const Helix helix;
  const SpeedFunction speed = [&](double t) { return helix.speed(t); };
  const double total = helix.length(0.0, 6.0);
  double worst_t = 0.0;
  for (double t : {0.0, 1e-9, 0.5, 1.234567, 3.0, 5.999, 6.0}) {
    const ArcLengthInverse inverse = parameter_at_arc_length(speed, 0.0, 6.0, helix.length(0.0, t));
    EXPECT_TRUE(inverse.converged);
    EXPECT_LE(std::abs(inverse.residual_mm), 1e-10);
    worst_t = std::max(worst_t, std::abs(inverse.t - t));
    EXPECT_LE(inverse.iterations, 8) << t;
  }
  std::printf("[figures] t(s(t)) - t over the helix: max %.2e\n", worst_t);
  EXPECT_LE(worst_t, 1e-11);
  EXPECT_THROW(parameter_at_arc_length(speed, 0.0, 6.0, total + 1e-3), Error);
  EXPECT_THROW(parameter_at_arc_length(speed, 0.0, 6.0, -1e-3), Error);
  EXPECT_THROW(parameter_at_arc_length(speed, 6.0, 0.0, 1.0), Error);
}

TEST(ArcLength, InverseSurvivesAVanishingSpeed) {
  // C(t) = (t^3, 0, 0) on [-1, 1]: the speed 3 t^2 is zero at t = 0, where Newton's step is undefined; s(t) = t^3 + 1.
  const SpeedFunction speed = [](double t) { return 3.0 * t * t; };
  for (double s : {0.0, 0.5, 1.0, 1.0 + 1e-12, 1.5, 2.0}) {
    const ArcLengthInverse inverse = parameter_at_arc_length(speed, -1.0, 1.0, s, 1e-12);
    EXPECT_TRUE(inverse.converged) << s;
    EXPECT_NEAR(inverse.t * inverse.t * inverse.t + 1.0, s, 1e-11) << s;
  }
}

TEST(ArcLength, ASpeedThatNeverSettlesStopsWithinTheBudget) {
  // 1 / sqrt|t - 1/3| is integrable (4 / sqrt(3) + ... ) but the rule never meets 1e-13 next to the singularity: the
  // refinement must stop at the evaluation budget, report it, and not recurse or hang.
  const SpeedFunction singular = [](double t) { return 1.0 / std::sqrt(std::abs(t - 1.0 / 3.0) + 1e-300); };
  ArcLengthOptions options;
  options.max_evaluations = 5000;
  const ArcLengthIntegral integral = integrate_arc_length(singular, 0.0, 1.0, options);
  EXPECT_FALSE(integral.converged);
  EXPECT_LE(integral.evaluations, 5000 + 20 * 62);  // the intervals still waiting get one rule each
  EXPECT_NEAR(integral.length_mm, 2.0 * (std::sqrt(1.0 / 3.0) + std::sqrt(2.0 / 3.0)), 0.05);
  EXPECT_THROW(arc_length(singular, 0.0, 1.0, options), Error);
  options.max_evaluations = 10;
  EXPECT_THROW(integrate_arc_length(singular, 0.0, 1.0, options), Error);  // invalid: below one rule's 30
}

TEST(ArcLength, RejectsBadInput) {
  const SpeedFunction speed = [](double) { return 1.0; };
  EXPECT_THROW(arc_length(speed, 0.0, std::nan("")), Error);
  ArcLengthOptions bad;
  bad.relative_tolerance = -1.0;
  EXPECT_THROW(arc_length(speed, 0.0, 1.0, bad), Error);
  // A speed with a non-integrable singularity does not converge: an error, not a number.
  const SpeedFunction singular = [](double t) { return 1.0 / (t * t); };
  EXPECT_THROW(arc_length(singular, 0.0, 1.0), Error);
}

}  // namespace
}  // namespace conform
