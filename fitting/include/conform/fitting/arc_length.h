#pragma once
// Arc length of a parametric space curve, s(t) = integral of |C'(tau)| from t0 to t, by adaptive Gauss-Legendre
// quadrature, and its inverse t(s) by safeguarded Newton. Any curve whose speed |C'(t)| can be evaluated: the
// polynomial and B-spline curves of this module, or a closed form in a test.
//
// Quadrature: 10-point Gauss-Legendre on an interval and on its two halves; where they differ by more than the
// interval's share of the tolerance, each half is refined in turn (Davis & Rabinowitz, Methods of Numerical
// Integration, 2nd ed., Sec. 6.2), from an explicit stack and within a budget of speed evaluations, so that a speed
// that never settles ends in converged = false, never in deep recursion or a hang. The nodes are computed once by Newton's method on the Legendre polynomial.
// Inverse: Newton's step t -= (s(t) - s) / |C'(t)| inside a bracket that shrinks at every step, falling back to
// bisection when the step leaves the bracket or the speed vanishes (Press et al., Numerical Recipes 3rd ed., 9.4).

#include <functional>
#include <string>

namespace conform {

// |C'(t)|, mm per unit of t.
using SpeedFunction = std::function<double(double t)>;

struct ArcLengthOptions {
  double relative_tolerance = 1e-13;  // of the length
  double absolute_tolerance_mm = 1e-15;
  int max_depth = 48;  // bisections of the interval at most
  long max_evaluations = 200000;  // speed evaluations at most (>= 30): the refinement stops there, not converged

  bool IsValid(std::string* error) const;
};

struct ArcLengthIntegral {
  double length_mm = 0.0;  // signed: negative when t1 < t0
  bool converged = false;  // every subinterval met its share of the tolerance before max_depth
  int evaluations = 0;     // speed evaluations
};

// Throws conform::Error for non-finite bounds or invalid options.
ArcLengthIntegral integrate_arc_length(const SpeedFunction& speed, double t0, double t1,
                                       const ArcLengthOptions& options = {});
// The length alone; throws conform::Error when the quadrature did not converge (a speed with a singularity).
double arc_length(const SpeedFunction& speed, double t0, double t1, const ArcLengthOptions& options = {});

struct ArcLengthInverse {
  double t = 0.0;
  bool converged = false;
  int iterations = 0;
  double residual_mm = 0.0;  // s(t) - s at the answer
};

// The t in [t0, t1] (t0 < t1) with arc_length(speed, t0, t) = s_mm, to tolerance_mm. Throws conform::Error when s_mm
// lies outside [0, arc_length(t0, t1)] (beyond the tolerance) or the bounds are not finite and increasing.
ArcLengthInverse parameter_at_arc_length(const SpeedFunction& speed, double t0, double t1, double s_mm,
                                         double tolerance_mm = 1e-10, const ArcLengthOptions& options = {});

}  // namespace conform
