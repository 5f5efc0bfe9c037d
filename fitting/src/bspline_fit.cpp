#include "conform/fitting/bspline_fit.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "conform/core/error.h"

namespace conform {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// The penalised least-squares system  (D + lambda P) C = R  with D = B^T W^2 B / sum w^2, R = B^T W^2 X / sum w^2.
struct SmoothingSystem {
  SparseMatrix data;
  SparseMatrix penalty;  // integral over v in [0, 1] of the second-derivative products
  Eigen::MatrixXd rhs;   // m x 3
  double weight_sum = 0.0;
};

std::vector<double> point_parameters(const std::vector<Eigen::Vector3d>& points, const BSplineFitOptions& o,
                                     double* u_end) {
  if (!o.parameters.empty()) {
    *u_end = o.parameters.back();
    return std::vector<double>(o.parameters.begin(), o.parameters.begin() + static_cast<std::ptrdiff_t>(points.size()));
  }
  std::vector<double> u(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) u[i] = u[i - 1] + (points[i] - points[i - 1]).norm();
  *u_end = u.back() + (o.closed ? (points.front() - points.back()).norm() : 0.0);
  if (!(*u_end > 0.0)) throw Error("fit_bspline_curve: all " + std::to_string(points.size()) + " points coincide");
  return u;
}

// G_kl = integral over a span of b_k''(x) b_l''(x) dx: 2-point Gauss-Legendre is exact for these quadratics.
Eigen::Matrix4d span_bending_gram() {
  const double offset = 0.5 / std::sqrt(3.0);
  Eigen::Matrix4d g = Eigen::Matrix4d::Zero();
  for (double x : {0.5 - offset, 0.5 + offset}) {
    double b[4];
    BSplineCurve::basis(x, 2, b);
    const Eigen::Vector4d v(b[0], b[1], b[2], b[3]);
    g += 0.5 * v * v.transpose();
  }
  return g;
}

SmoothingSystem build_system(const BSplineCurve& shape, const std::vector<Eigen::Vector3d>& points,
                             const std::vector<double>& u, const std::vector<double>& weights) {
  const auto m = static_cast<Eigen::Index>(shape.control_points().size());
  SmoothingSystem s;
  s.rhs = Eigen::MatrixXd::Zero(m, 3);
  for (std::size_t i = 0; i < points.size(); ++i) s.weight_sum += weights.empty() ? 1.0 : weights[i] * weights[i];
  std::vector<Eigen::Triplet<double>> data;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double w2 = (weights.empty() ? 1.0 : weights[i] * weights[i]) / s.weight_sum;
    int span = 0, idx[4];
    double x = 0.0, b[4];
    shape.locate(u[i], &span, &x, idx);
    BSplineCurve::basis(x, 0, b);
    for (int k = 0; k < 4; ++k) {
      s.rhs.row(idx[k]) += w2 * b[k] * points[i].transpose();
      for (int l = 0; l < 4; ++l) data.emplace_back(idx[k], idx[l], w2 * b[k] * b[l]);
    }
  }
  // Over v in [0, 1] a span has length 1 / n, so d^2/dv^2 = n^2 d^2/dx^2 and dv = dx / n: a factor n^3 per span.
  const Eigen::Matrix4d gram = span_bending_gram();
  const double n = shape.spans();
  std::vector<Eigen::Triplet<double>> bending;
  for (int j = 0; j < shape.spans(); ++j) {
    int span = 0, idx[4];
    double x = 0.0;
    shape.locate(shape.u_begin() + (j + 0.5) * shape.knot_spacing(), &span, &x, idx);
    for (int k = 0; k < 4; ++k) {
      for (int l = 0; l < 4; ++l) bending.emplace_back(idx[k], idx[l], n * n * n * gram(k, l));
    }
  }
  s.data.resize(m, m);
  s.data.setFromTriplets(data.begin(), data.end());
  s.penalty.resize(m, m);
  s.penalty.setFromTriplets(bending.begin(), bending.end());
  return s;
}

struct Solution {
  bool solvable = false;
  std::vector<Eigen::Vector3d> control;
  double weighted_ss_mm2 = 0.0;
};

Solution solve(const SmoothingSystem& s, double lambda, const BSplineCurve& shape,
               const std::vector<Eigen::Vector3d>& points, const std::vector<double>& u,
               const std::vector<double>& weights) {
  Solution out;
  const SparseMatrix a = s.data + lambda * s.penalty;
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);
  if (ldlt.info() != Eigen::Success) return out;
  // A semi-definite system (a span without points and no smoothing) factors with a (near) zero pivot.
  const Eigen::VectorXd d = ldlt.vectorD();
  if (!(d.minCoeff() > 1e-13 * d.maxCoeff())) return out;
  const Eigen::MatrixXd c = ldlt.solve(s.rhs);
  out.control.resize(static_cast<std::size_t>(c.rows()));
  for (Eigen::Index i = 0; i < c.rows(); ++i) out.control[static_cast<std::size_t>(i)] = c.row(i).transpose();
  const BSplineCurve curve(out.control, shape.closed(), shape.u_begin(), shape.u_end());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double w2 = weights.empty() ? 1.0 : weights[i] * weights[i];
    out.weighted_ss_mm2 += w2 * (points[i] - curve.position(u[i])).squaredNorm();
  }
  out.solvable = c.allFinite() && std::isfinite(out.weighted_ss_mm2);
  return out;
}

struct Search {
  double lambda = 0.0;
  Solution solution;
  int iterations = 0;
  bool met = false;
  std::string why;  // when the target was not met
};

// Bisection in log lambda on the weighted residual sum of squares, which grows with lambda (Reinsch 1967).
Search search_lambda(const SmoothingSystem& s, const BSplineCurve& shape, const std::vector<Eigen::Vector3d>& points,
                     const std::vector<double>& u, const BSplineFitOptions& o) {
  const double target = o.smoothing_mm2;
  const double tolerance = o.smoothing_tolerance * std::max(target, 1e-300);
  const auto run = [&](double lambda, Search* out) {
    ++out->iterations;
    out->lambda = lambda;
    out->solution = solve(s, lambda, shape, points, u, o.weights);
    return out->solution.solvable;
  };
  Search out;
  // The closest fit: lambda 0, or the smallest weight that makes the system solvable.
  double lo = 0.0;
  while (!run(lo, &out)) {
    lo = lo == 0.0 ? 1e-14 : lo * 100.0;
    if (lo > 1e6) throw Error("fit_bspline_curve: the smoothing system is singular for every lambda");
  }
  if (out.solution.weighted_ss_mm2 >= target - tolerance) {
    out.met = std::abs(out.solution.weighted_ss_mm2 - target) <= tolerance;
    out.why = "the closest fit with these control points leaves " + std::to_string(out.solution.weighted_ss_mm2) +
              " mm^2 > smoothing_mm2; use more control points";
    return out;
  }
  double hi = std::max(1.0, lo * 100.0);
  Search high;
  while (run(hi, &high) && high.solution.weighted_ss_mm2 < target && hi < 1e30) hi *= 100.0;
  out.iterations += high.iterations;
  if (!high.solution.solvable || high.solution.weighted_ss_mm2 < target) {
    const int iterations = out.iterations;
    out = high;
    out.iterations = iterations;
    out.why = "even the smoothest curve stays within smoothing_mm2 (a straight line, or a point when closed)";
    return out;
  }
  for (int i = 0; i < 200; ++i) {
    const double mid = lo == 0.0 ? hi * 1e-12 : std::sqrt(lo * hi);
    Search probe;
    run(mid, &probe);
    out.iterations += probe.iterations;
    if (!probe.solution.solvable || probe.solution.weighted_ss_mm2 < target) {
      lo = mid;
    } else {
      hi = mid;
    }
    if (probe.solution.solvable) {
      out.lambda = probe.lambda;
      out.solution = probe.solution;
      if (std::abs(probe.solution.weighted_ss_mm2 - target) <= tolerance) {
        out.met = true;
        return out;
      }
    }
    if (hi <= lo * (1.0 + 1e-15)) break;
  }
  out.why = "the lambda search stopped before the target";
  return out;
}

// trace((D + lambda P)^-1 D), one banded solve per column of D.
double effective_dof(const SmoothingSystem& s, double lambda) {
  const SparseMatrix a = s.data + lambda * s.penalty;
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(a);
  if (ldlt.info() != Eigen::Success) return 0.0;
  double trace = 0.0;
  for (Eigen::Index j = 0; j < s.data.cols(); ++j) {
    const Eigen::VectorXd column = Eigen::VectorXd(s.data.col(j));
    trace += ldlt.solve(column)(j);
  }
  return trace;
}

void check_inputs(const std::vector<Eigen::Vector3d>& points, const BSplineFitOptions& o) {
  std::string why;
  if (!o.IsValid(&why)) throw Error("fit_bspline_curve: " + why);
  if (points.size() < 4) {
    throw Error("fit_bspline_curve: " + std::to_string(points.size()) + " points; a cubic B-spline needs at least 4");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error("fit_bspline_curve: point " + std::to_string(i) + " is not finite");
  }
  if (std::all_of(points.begin(), points.end(), [&](const Eigen::Vector3d& p) { return p == points.front(); })) {
    throw Error("fit_bspline_curve: all " + std::to_string(points.size()) + " points coincide");
  }
  const std::size_t expected = points.size() + (o.closed ? 1 : 0);
  if (!o.parameters.empty() && o.parameters.size() != expected) {
    throw Error("fit_bspline_curve: " + std::to_string(o.parameters.size()) + " parameters for " +
                std::to_string(points.size()) + " points; need " + std::to_string(expected) +
                (o.closed ? " (closed: one per point, then the period's end)" : ""));
  }
  if (!o.weights.empty() && o.weights.size() != points.size()) {
    throw Error("fit_bspline_curve: " + std::to_string(o.weights.size()) + " weights for " +
                std::to_string(points.size()) + " points");
  }
}

}  // namespace

bool BSplineFitOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (control_points != 0 && control_points < 4) return fail("control_points must be 0 (automatic) or >= 4");
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (!std::isfinite(parameters[i])) return fail("parameter " + std::to_string(i) + " is not finite");
    if (i > 0 && parameters[i] < parameters[i - 1]) return fail("parameter " + std::to_string(i) + " decreases");
  }
  if (!parameters.empty() && !(parameters.back() > parameters.front())) {
    return fail("the parameters must span an interval (last > first)");
  }
  for (std::size_t i = 0; i < weights.size(); ++i) {
    if (!(weights[i] > 0.0) || !std::isfinite(weights[i])) return fail("weight " + std::to_string(i) + " must be > 0");
  }
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) return fail("lambda must be >= 0");
  if (!std::isfinite(smoothing_mm2)) return fail("smoothing_mm2 must be finite (< 0: use lambda)");
  if (!(smoothing_tolerance > 0.0 && smoothing_tolerance < 1.0)) return fail("smoothing_tolerance must be in (0, 1)");
  return true;
}

BSplineFit fit_bspline_curve(const std::vector<Eigen::Vector3d>& points, const BSplineFitOptions& options) {
  check_inputs(points, options);
  BSplineFit fit;
  double u_end = 0.0;
  fit.parameters = point_parameters(points, options, &u_end);
  const int n = static_cast<int>(points.size());
  const int m = options.control_points > 0 ? options.control_points : std::min(n, std::clamp(n / 2, 8, 4000));
  const BSplineCurve shape(std::vector<Eigen::Vector3d>(static_cast<std::size_t>(m), Eigen::Vector3d::Zero()),
                           options.closed, fit.parameters.front(), u_end);
  const SmoothingSystem system = build_system(shape, points, fit.parameters, options.weights);

  Solution solution;
  if (options.smoothing_mm2 >= 0.0) {
    const Search search = search_lambda(system, shape, points, fit.parameters, options);
    solution = search.solution;
    fit.lambda = search.lambda;
    fit.lambda_iterations = search.iterations;
    fit.converged = search.met;
    fit.termination = search.met ? "ok" : search.why;
  } else {
    solution = solve(system, options.lambda, shape, points, fit.parameters, options.weights);
    fit.lambda = options.lambda;
    if (!solution.solvable) {
      throw Error("fit_bspline_curve: the system is singular: " + std::to_string(m) + " control points for " +
                  std::to_string(n) + " points without smoothing; give lambda > 0 or fewer control points");
    }
    fit.converged = true;
    fit.termination = "ok";
  }
  fit.curve = BSplineCurve(solution.control, options.closed, fit.parameters.front(), u_end);
  if (options.effective_dof) fit.effective_dof = effective_dof(system, fit.lambda);
  fit.weighted_ss_mm2 = solution.weighted_ss_mm2;
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    fit.residual_mm.push_back((points[i] - fit.curve.position(fit.parameters[i])).norm());
    sum_squares += fit.residual_mm.back() * fit.residual_mm.back();
    fit.max_residual_mm = std::max(fit.max_residual_mm, fit.residual_mm.back());
  }
  fit.rms_mm = std::sqrt(sum_squares / n);
  fit.ok = std::isfinite(fit.rms_mm);
  fit.converged = fit.converged && fit.ok;
  return fit;
}

}  // namespace conform
