#include "conform/toolpath/saddle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kTwoPi = 6.283185307179586;
// A step that ends within this fraction of itself from 2 pi lands on 2 pi as a full step.
constexpr double kLandingTolerance = 1e-9;
// Per-step solves stop when the step changes by less than this many rounding units of the azimuth it reaches: below
// that, theta + dtheta itself cannot move.
constexpr double kSolveUlps = 8.0 * std::numeric_limits<double>::epsilon();
constexpr int kMaxFixedPointIterations = 60;
constexpr int kMaxBracketIterations = 200;

struct StepSolve {
  double step_rad = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Safeguarded root of f on (0, hi] with f(0) < 0 <= f(hi), f increasing through the root: Newton (or the
// given fixed-point guess) inside the bracket, bisection when a proposal leaves it.
template <typename F, typename Next>
StepSolve bracketed_solve(double guess, double hi, double tolerance, const F& f, const Next& next,
                          int first_iterations) {
  double lo = 0.0;
  double x = std::clamp(guess, 0.0, hi);
  StepSolve solve;
  solve.iterations = first_iterations;
  for (int k = 0; k < kMaxBracketIterations; ++k) {
    ++solve.iterations;
    const double value = f(x);
    if (value < 0.0) lo = x;
    if (value >= 0.0) hi = x;
    double proposal = next(x, value);
    // A proposal that has settled is accepted even on the bracket's edge (value 0 makes x an edge).
    bool done = value == 0.0 || std::abs(proposal - x) <= tolerance;
    if (!done && !(proposal > lo && proposal < hi)) {
      proposal = 0.5 * (lo + hi);
      done = hi - lo <= tolerance;
    }
    if (value != 0.0) x = proposal;
    if (done) {
      solve.step_rad = x;
      solve.converged = true;
      return solve;
    }
  }
  solve.step_rad = x;
  return solve;
}

// Eq. 24: dtheta = v dT sin(alpha(theta + dtheta / 2)) / r. Fixed-point iteration (a contraction for v dT well below
// r); if it has not settled, the same equation is solved in its bracket (0, v dT / r], since sin(alpha) <= 1.
StepSolve variable_angle_step(const SaddleCurve& curve, double theta, double step_mm) {
  const double r = curve.geometry().pipe_radius_mm;
  const double tolerance = kSolveUlps * (theta + step_mm / r);
  const auto fixed_point = [&](double step) { return step_mm * curve.sin_alpha(theta + 0.5 * step) / r; };
  double step = fixed_point(0.0);
  for (int k = 1; k <= kMaxFixedPointIterations; ++k) {
    const double next = fixed_point(step);
    if (std::abs(next - step) <= tolerance) return {next, k, true};
    step = next;
  }
  const auto f = [&](double x) { return x - fixed_point(x); };
  const auto bisect = [](double, double) { return -1.0; };
  return bracketed_solve(step, step_mm / r, tolerance, f, bisect, kMaxFixedPointIterations);
}

// Beyond the paper: the arc length of the step is exactly v dT. Newton's method on s(theta, theta + dtheta) - v dT,
// whose derivative is |dP/dtheta| >= r, so the root lies in (0, v dT / r].
StepSolve arc_length_step(const SaddleCurve& curve, double theta, double step_mm) {
  const double r = curve.geometry().pipe_radius_mm;
  const auto f = [&](double x) { return curve.arc_length(theta, theta + x) - step_mm; };
  const auto newton = [&](double x, double value) { return x - value / curve.derivative(theta + x).norm(); };
  const double tolerance = kSolveUlps * (theta + step_mm / r);
  return bracketed_solve(step_mm / curve.derivative(theta).norm(), step_mm / r, tolerance, f, newton, 0);
}

// Azimuths of equal-angle interpolation: i dtheta, then 2 pi.
std::vector<double> equal_angle_thetas(double step_rad, bool* last_partial) {
  const auto steps = static_cast<std::size_t>(std::ceil(kTwoPi / step_rad - kLandingTolerance));
  std::vector<double> thetas;
  thetas.reserve(steps + 1);
  for (std::size_t i = 0; i < steps; ++i) thetas.push_back(static_cast<double>(i) * step_rad);
  thetas.push_back(kTwoPi);
  *last_partial = kTwoPi - thetas[steps - 1] < step_rad * (1.0 - kLandingTolerance);
  return thetas;
}

// Azimuths of the constant-speed rules: one solve per period until the step reaches 2 pi.
std::vector<double> constant_speed_thetas(const SaddleCurve& curve, const SaddleOptions& options, std::size_t expected,
                                          SaddleResult* result) {
  const double step_mm = options.speed_mm_per_s * options.period_s;
  std::vector<double> thetas;
  thetas.reserve(expected);
  thetas.push_back(0.0);
  result->converged = true;
  for (double theta = 0.0;;) {
    const StepSolve solve = options.rule == SaddleStepRule::kVariableAngle ? variable_angle_step(curve, theta, step_mm)
                                                                           : arc_length_step(curve, theta, step_mm);
    result->max_iterations = std::max(result->max_iterations, solve.iterations);
    if (!solve.converged && result->converged) {
      result->converged = false;
      std::ostringstream why;
      why << "the step equation did not converge at theta = " << theta << " rad";
      result->termination = why.str();
    }
    const double end = theta + solve.step_rad;
    if (end >= kTwoPi - kLandingTolerance * solve.step_rad) {
      result->last_step_partial = end > kTwoPi + kLandingTolerance * solve.step_rad;
      thetas.push_back(kTwoPi);
      return thetas;
    }
    thetas.push_back(end);
    theta = end;
  }
}

void compute_figures(const SaddleCurve& curve, SaddleResult* result) {
  auto& points = result->points;
  const std::size_t steps = points.size() - 1;
  result->full_steps = result->last_step_partial && steps > 1 ? steps - 1 : steps;
  result->step_mm_min = std::numeric_limits<double>::infinity();
  result->step_mm_max = 0.0;
  double sum = 0.0;
  for (std::size_t i = 1; i <= steps; ++i) {
    result->path_length_mm += points[i].step_mm;
    if (i > result->full_steps) continue;
    result->step_mm_min = std::min(result->step_mm_min, points[i].step_mm);
    result->step_mm_max = std::max(result->step_mm_max, points[i].step_mm);
    sum += points[i].step_mm;
  }
  result->step_mm_mean = sum / static_cast<double>(result->full_steps);
  result->speed_ripple_pct = 100.0 * (result->step_mm_max - result->step_mm_min) / result->step_mm_mean;
  result->last_step_mm = points.back().step_mm;
  result->curve_length_mm = curve.arc_length(0.0, kTwoPi);
  result->pose_rad_min = std::numeric_limits<double>::infinity();
  result->pose_rad_max = -std::numeric_limits<double>::infinity();
  for (const SaddlePoint& point : points) {
    result->pose_rad_min = std::min(result->pose_rad_min, point.pose_rad);
    result->pose_rad_max = std::max(result->pose_rad_max, point.pose_rad);
    result->max_pipe_residual_mm = std::max(result->max_pipe_residual_mm, curve.pipe_residual(point.position));
    result->max_leg_residual_mm = std::max(result->max_leg_residual_mm, curve.leg_residual(point.position));
  }
}

}  // namespace

const char* to_string(SaddleStepRule rule) {
  switch (rule) {
    case SaddleStepRule::kEqualAngle:
      return "equal-angle";
    case SaddleStepRule::kVariableAngle:
      return "variable-angle";
    case SaddleStepRule::kArcLength:
      return "arc-length";
  }
  return "unknown";
}

bool SaddleOptions::IsValid(std::string* error) const {
  if (!geometry.IsValid(error)) return false;
  std::ostringstream why;
  if (!std::isfinite(start_pose_rad)) {
    why << "the start pose angle must be a finite number";
  } else if (rule == SaddleStepRule::kEqualAngle) {
    if (!(step_rad > 0.0 && step_rad <= kTwoPi)) {
      why << "the angle step " << step_rad * 360.0 / kTwoPi << " deg is outside (0, 360] deg";
    }
  } else if (!(speed_mm_per_s > 0.0) || !std::isfinite(speed_mm_per_s)) {
    why << "the speed " << speed_mm_per_s << " mm/s must be a positive number";
  } else if (!(period_s > 0.0) || !std::isfinite(period_s)) {
    why << "the interpolation period " << period_s << " s must be a positive number";
  } else if (!(speed_mm_per_s * period_s <= geometry.pipe_radius_mm)) {
    why << "the step speed * period = " << speed_mm_per_s * period_s
        << " mm is longer than the pipe radius r = " << geometry.pipe_radius_mm
        << " mm: the path would cut across the seam; use a shorter period";
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

SaddleResult interpolate_saddle(const SaddleOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw Error("saddle: " + error);
  const SaddleCurve curve(options.geometry);

  const bool equal_angle = options.rule == SaddleStepRule::kEqualAngle;
  const double expected = equal_angle
                              ? kTwoPi / options.step_rad + 2.0
                              : curve.arc_length(0.0, kTwoPi) / (options.speed_mm_per_s * options.period_s) + 2.0;
  if (!(expected <= static_cast<double>(options.max_points))) {
    std::ostringstream why;
    why << "saddle: the step is too small: the path would need about " << std::llround(std::min(expected, 1e18))
        << " points, more than the limit of " << options.max_points << "; use a larger step";
    throw Error(why.str());
  }

  SaddleResult result;
  result.rule = options.rule;
  result.termination = "ok";
  std::vector<double> thetas;
  if (equal_angle) {
    thetas = equal_angle_thetas(options.step_rad, &result.last_step_partial);
    result.converged = true;
  } else {
    thetas = constant_speed_thetas(curve, options, static_cast<std::size_t>(expected), &result);
  }

  result.points.reserve(thetas.size());
  for (std::size_t i = 0; i < thetas.size(); ++i) {
    SaddlePoint point;
    point.theta_rad = thetas[i];
    point.position = curve.point(thetas[i]);
    point.pose_rad = curve.pose(thetas[i], options.start_pose_rad);
    if (i > 0) point.step_mm = (point.position - result.points.back().position).norm();
    result.points.push_back(point);
  }
  compute_figures(curve, &result);
  return result;
}

}  // namespace conform
