#pragma once
// A smoothing cubic B-spline through ordered points, open or closed (periodic): the role of scipy's
// splprep(..., per=1) for closed intersection paths, and of a long profile's edge curve where one global cubic is too
// stiff. Penalised least squares on uniform knots (Eilers & Marx 1996, with the exact bending energy instead of
// their difference penalty; Reinsch 1967 for the smoothing target):
//
//   minimise  sum_i w_i^2 |P_i - S(u_i)|^2 / sum_i w_i^2  +  lambda * integral_0^1 |d^2 S / dv^2|^2 dv
//
// over the control points, where v = (u - u_begin) / (u_end - u_begin) runs over [0, 1], so lambda is dimensionless
// (both terms are mm^2). The normal equations are banded (cyclically banded when closed) and solved by a sparse LDLT.
// With smoothing_mm2 >= 0, lambda is chosen so that sum_i w_i^2 |P_i - S(u_i)|^2 = smoothing_mm2 (splprep's s; for
// noise of sigma per coordinate, about 3 n sigma^2), by bisection in log lambda.
//
//   BSplineFitOptions options;
//   options.closed = true;
//   options.smoothing_mm2 = 3.0 * points.size() * sigma * sigma;
//   const BSplineFit fit = fit_bspline_curve(points, options);
//   const Eigen::Vector3d tangent = fit.curve.derivative(fit.parameters[17]).normalized();

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/bspline_curve.h"

namespace conform {

struct BSplineFitOptions {
  bool closed = false;     // periodic: the curve returns to its start, C2 across the seam
  int control_points = 0;  // 0: automatic, clamp(n / 2, 8, 4000) for n points (never more than n when lambda is 0)
  // The parameter u_i of each point; empty: chord length (mm) from the first point. Increasing (equal values allowed).
  // Closed: n + 1 values, the last being where the curve is back at the first point (the period's end).
  std::vector<double> parameters;
  std::vector<double> weights;        // w_i > 0, one per point; empty: all 1
  double lambda = 0.0;                // the bending-energy weight, when smoothing_mm2 < 0
  double smoothing_mm2 = -1.0;        // >= 0: choose lambda so that the weighted residual sum of squares equals this
  double smoothing_tolerance = 1e-6;  // relative, on smoothing_mm2, for the lambda search
  bool effective_dof = false;         // also compute the smoother's effective degrees of freedom (O(m^2) more work)

  bool IsValid(std::string* error) const;
};

struct BSplineFit {
  BSplineCurve curve;
  bool ok = false;         // the system was solvable and the residuals finite
  bool converged = false;  // ok, and (with a smoothing target) the target was met to its tolerance
  std::string termination = "not run";
  std::vector<double> parameters;   // u_i of the points
  std::vector<double> residual_mm;  // |P_i - S(u_i)|
  double rms_mm = 0.0;
  double max_residual_mm = 0.0;
  double weighted_ss_mm2 = 0.0;  // sum_i w_i^2 |P_i - S(u_i)|^2
  double lambda = 0.0;           // the weight used
  int lambda_iterations = 0;     // solves of the lambda search (0 without a target)
  // trace of the smoother matrix (D + lambda P)^-1 D per coordinate: from m (lambda 0) down to 2 (a straight line);
  // 0 unless options.effective_dof (Hastie & Tibshirani, Generalized Additive Models, Sec. 3.5).
  double effective_dof = 0.0;
};

// Throws conform::Error when the options are invalid (parameter or weight counts, a decreasing parameter, ...),
// a point is not finite, there are fewer than 4 points, all points coincide, or the system is singular (more control
// points than the points can determine without smoothing: give lambda > 0 or fewer control points).
BSplineFit fit_bspline_curve(const std::vector<Eigen::Vector3d>& points, const BSplineFitOptions& options);

}  // namespace conform
