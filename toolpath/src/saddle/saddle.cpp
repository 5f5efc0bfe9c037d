#include "conform/toolpath/saddle/saddle.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

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

// Azimuths of the constant-speed rules: one solve per period until the step reaches 2 pi. A step that would pass over
// a corner of the seam (|offset| + r = R) ends on it instead: no chord cuts the corner, and the torch reaches the
// point where the pipe touches the cylinder; such a step is shortened (and left out of the step figures).
std::vector<double> constant_speed_thetas(const SaddleCurve& curve, const SaddleOptions& options, std::size_t expected,
                                          SaddleResult* result, std::vector<bool>* shortened) {
  const double step_mm = options.speed_mm_per_s * options.period_s;
  const std::vector<double> corners = curve.corners();
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
    double end = theta + solve.step_rad;
    if (end >= kTwoPi - kLandingTolerance * solve.step_rad) {
      result->last_step_partial = end > kTwoPi + kLandingTolerance * solve.step_rad;
      shortened->push_back(result->last_step_partial);
      thetas.push_back(kTwoPi);
      return thetas;
    }
    bool short_step = false;
    for (double corner : corners) {
      if (theta < corner && end > corner - kLandingTolerance * solve.step_rad) {
        short_step = end > corner + kLandingTolerance * solve.step_rad;
        end = corner;
      }
    }
    result->corner_steps += short_step ? 1 : 0;
    shortened->push_back(short_step);
    thetas.push_back(end);
    theta = end;
  }
}

// shortened[i - 1]: step i ended early (on 2 pi or on a corner): left out of the step figures, unless it is all.
void compute_figures(const SaddleCurve& curve, const std::vector<bool>& shortened, SaddleResult* result) {
  auto& points = result->points;
  const std::size_t steps = points.size() - 1;
  const auto left_out = [&](std::size_t i) { return steps > 1 && shortened[i - 1]; };
  result->full_steps = 0;
  for (std::size_t i = 1; i <= steps; ++i) result->full_steps += left_out(i) ? 0 : 1;
  result->step_mm_min = std::numeric_limits<double>::infinity();
  result->step_mm_max = 0.0;
  double sum = 0.0;
  for (std::size_t i = 1; i <= steps; ++i) {
    result->path_length_mm += points[i].step_mm;
    if (left_out(i)) continue;
    result->step_mm_min = std::min(result->step_mm_min, points[i].step_mm);
    result->step_mm_max = std::max(result->step_mm_max, points[i].step_mm);
    sum += points[i].step_mm;
  }
  result->step_mm_mean = sum / static_cast<double>(result->full_steps);
  result->speed_ripple_pct = 100.0 * (result->step_mm_max - result->step_mm_min) / result->step_mm_mean;
  result->last_step_mm = points.back().step_mm;
  bool length_converged = true;
  result->curve_length_mm = curve.arc_length(0.0, kTwoPi, &length_converged);
  // Chords are never longer than the arcs they span: a polyline longer than the seam is a failed quadrature.
  if (result->converged && (!length_converged || result->path_length_mm > result->curve_length_mm * (1.0 + 1e-9))) {
    result->converged = false;
    std::ostringstream why;
    why.precision(12);
    why << "the seam's arc length did not converge (seam " << result->curve_length_mm << " mm, path "
        << result->path_length_mm << " mm)";
    result->termination = why.str();
  }
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
  if (!(start_pose_rad > -kPi && start_pose_rad <= kPi)) {
    why << "the pose angle at a right-angle dihedral " << start_pose_rad * 180.0 / kPi
        << " deg must be a number in (-180, 180] deg";
  } else if (rule == SaddleStepRule::kEqualAngle) {
    if (!(step_rad > 0.0 && step_rad < kPi)) {
      why << "the angle step " << step_rad * 180.0 / kPi
          << " deg is outside (0, 180) deg (a half turn or more skips the seam's far side)";
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
  std::vector<bool> shortened;
  if (equal_angle) {
    thetas = equal_angle_thetas(options.step_rad, &result.last_step_partial);
    shortened.assign(thetas.size() - 1, false);
    shortened.back() = result.last_step_partial;
    result.converged = true;
  } else {
    thetas = constant_speed_thetas(curve, options, static_cast<std::size_t>(expected), &result, &shortened);
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
  compute_figures(curve, shortened, &result);
  return result;
}

}  // namespace conform
