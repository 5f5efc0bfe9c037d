#include "conform/fitting/arc_length.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

constexpr int kNodes = 10;

struct GaussLegendreRule {
  std::array<double, kNodes> x{};  // nodes on [-1, 1]
  std::array<double, kNodes> w{};  // weights, summing to 2
};

// Legendre P_n(x) and its derivative by the three-term recurrence (k P_k = (2k - 1) x P_{k-1} - (k - 1) P_{k-2}).
void legendre(double x, double* p, double* dp) {
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= kNodes; ++k) {
    const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  *p = p1;
  *dp = kNodes * (x * p1 - p0) / (x * x - 1.0);
}

// The nodes are the roots of P_n, found by Newton's method from Tricomi's estimate cos(pi (i + 3/4) / (n + 1/2));
// the weights are 2 / ((1 - x^2) P_n'(x)^2) (Abramowitz & Stegun 25.4.29).
GaussLegendreRule make_rule() {
  GaussLegendreRule rule;
  for (int i = 0; i < kNodes; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (kNodes + 0.5));
    double p = 0.0, dp = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      legendre(x, &p, &dp);
      const double step = p / dp;
      x -= step;
      if (std::abs(step) <= 1e-17) break;
    }
    legendre(x, &p, &dp);
    rule.x[static_cast<std::size_t>(i)] = x;
    rule.w[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

const GaussLegendreRule& rule() {
  static const GaussLegendreRule instance = make_rule();
  return instance;
}

struct Quadrature {
  const SpeedFunction& speed;
  double tolerance_per_t;  // the tolerance's share per unit of parameter
  int max_depth;
  long max_evaluations;
  long evaluations = 0;
  bool converged = true;

  double gauss(double a, double b) {
    const GaussLegendreRule& r = rule();
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    double sum = 0.0;
    for (std::size_t i = 0; i < kNodes; ++i) sum += r.w[i] * speed(mid + half * r.x[i]);
    evaluations += kNodes;
    return half * sum;
  }

  // `whole` is the rule on [a, b]; the two halves replace it when they agree with it, otherwise each is refined.
  // An explicit stack, not recursion, and a budget of speed evaluations: a speed that never settles (a singularity,
  // or digits lost far from the origin) ends the refinement with converged = false instead of hanging.
  double integrate(double a0, double b0, double whole0) {
    struct Interval {
      double a, b, whole;
      int depth;
    };
    // Depth first: never more than max_depth + 1 (<= 61) intervals wait, so a fixed array serves (no allocation).
    std::array<Interval, 64> stack;
    std::size_t size = 0;
    stack[size++] = {a0, b0, whole0, 0};
    double total = 0.0;
    while (size > 0) {
      const Interval in = stack[--size];
      const double mid = 0.5 * (in.a + in.b);
      const double left = gauss(in.a, mid), right = gauss(mid, in.b);
      const double both = left + right;
      const bool met = std::abs(both - in.whole) <= tolerance_per_t * std::abs(in.b - in.a);
      const bool stuck = in.depth >= max_depth || !(mid != in.a && mid != in.b) || evaluations >= max_evaluations;
      if (met || stuck) {
        if (!met) converged = false;
        total += both;
        continue;
      }
      stack[size++] = {mid, in.b, right, in.depth + 1};
      stack[size++] = {in.a, mid, left, in.depth + 1};
    }
    return total;
  }
};

}  // namespace

bool ArcLengthOptions::IsValid(std::string* error) const {
  const auto fail = [error](const char* why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (!(relative_tolerance >= 0.0) || !std::isfinite(relative_tolerance))
    return fail("relative_tolerance must be >= 0");
  if (!(absolute_tolerance_mm >= 0.0) || !std::isfinite(absolute_tolerance_mm)) {
    return fail("absolute_tolerance_mm must be >= 0");
  }
  if (!(relative_tolerance > 0.0 || absolute_tolerance_mm > 0.0)) return fail("one of the tolerances must be > 0");
  if (max_depth < 0 || max_depth > 60) return fail("max_depth must be in [0, 60]");
  if (max_evaluations < 30) return fail("max_evaluations must be at least 30");
  return true;
}

ArcLengthIntegral integrate_arc_length(const SpeedFunction& speed, double t0, double t1,
                                       const ArcLengthOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("arc length: " + why);
  if (!std::isfinite(t0) || !std::isfinite(t1)) throw Error("arc length: the parameter bounds must be finite");
  ArcLengthIntegral out;
  if (t0 == t1) {
    out.converged = true;
    return out;
  }
  Quadrature q{speed, 0.0, options.max_depth, options.max_evaluations};
  const double whole = q.gauss(t0, t1);
  const double tolerance = std::max(options.absolute_tolerance_mm, options.relative_tolerance * std::abs(whole));
  q.tolerance_per_t = tolerance / std::abs(t1 - t0);
  out.length_mm = q.integrate(t0, t1, whole);
  out.converged = q.converged && std::isfinite(out.length_mm);
  out.evaluations = static_cast<int>(std::min<long>(q.evaluations, INT32_MAX));
  return out;
}

double arc_length(const SpeedFunction& speed, double t0, double t1, const ArcLengthOptions& options) {
  const ArcLengthIntegral integral = integrate_arc_length(speed, t0, t1, options);
  if (!integral.converged) {
    throw Error("arc length: the quadrature did not converge on [" + std::to_string(t0) + ", " + std::to_string(t1) +
                "] within " + std::to_string(integral.evaluations) +
                " speed evaluations (is the speed singular there, or the curve far from the origin?)");
  }
  return integral.length_mm;
}

ArcLengthInverse parameter_at_arc_length(const SpeedFunction& speed, double t0, double t1, double s_mm,
                                         double tolerance_mm, const ArcLengthOptions& options) {
  if (!(std::isfinite(t0) && std::isfinite(t1) && t0 < t1)) {
    throw Error("arc length inverse: the parameter interval must be finite and increasing");
  }
  if (!(tolerance_mm > 0.0)) throw Error("arc length inverse: the tolerance must be > 0");
  const double total = arc_length(speed, t0, t1, options);
  if (!std::isfinite(s_mm) || s_mm < -tolerance_mm || s_mm > total + tolerance_mm) {
    throw Error("arc length inverse: s = " + std::to_string(s_mm) + " mm lies outside the curve's [0, " +
                std::to_string(total) + "] mm");
  }
  const double s = std::clamp(s_mm, 0.0, total);
  ArcLengthInverse out;
  double lo = t0, hi = t1;
  double t = total > 0.0 ? t0 + (t1 - t0) * (s / total) : t0;
  double st = arc_length(speed, t0, t, options);
  for (; out.iterations < 200; ++out.iterations) {
    const double f = st - s;
    if (std::abs(f) <= tolerance_mm) break;
    (f > 0.0 ? hi : lo) = t;
    const double v = speed(t);
    double next = t - f / v;
    if (!(v > 0.0) || !(next > lo && next < hi)) next = 0.5 * (lo + hi);  // the safeguard: bisect the bracket
    if (next == t) break;                                                 // the bracket has collapsed onto t
    st += arc_length(speed, t, next, options);
    t = next;
  }
  out.t = t;
  out.residual_mm = st - s;
  out.converged = std::abs(out.residual_mm) <= tolerance_mm;
  return out;
}

}  // namespace conform
