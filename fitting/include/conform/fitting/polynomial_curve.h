#pragma once
// A least-squares polynomial space curve over the chord-length parameter, as fitted to the edge points of a deformed
// profile (Chen et al., LNG profiles): t_i = (chord length from P_0 to P_i) / (total chord length), and
// C(t) = Q_0 + Q_1 t + ... + Q_n t^n in each coordinate (degree n, default 3).
//
// The solve is a Householder QR of the basis matrix, never the normal equations (which square its condition number):
// the basis is the powers of u = (2 t - t_lo - t_hi) / (t_hi - t_lo), which maps the data's parameter range
// [t_lo, t_hi] ([0, 1] for chord length) onto [-1, 1] (centred, so that the columns are far less alike than the powers
// of t on [0, 1]), each column scaled to unit length. The curve keeps its coefficients in u and evaluates them by
// Horner's rule; power_coefficients() gives the Q_k in t.
//
//   const PolynomialCurveFit fit = fit_polynomial_curve(edge_points, {});
//   const double length = fit.curve.arc_length(0.0, 1.0);
//   const double t = fit.curve.parameter_at_arc_length(0.25 * length).t;  // a quarter of the way along
//   const Eigen::Vector3d tangent = fit.curve.derivative(t).normalized();

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/arc_length.h"

namespace conform {

class PolynomialCurve {
 public:
  PolynomialCurve() = default;
  // From power coefficients in t (Q_0 first): C(t) = sum Q_k t^k. Throws conform::Error when empty or not finite.
  static PolynomialCurve from_power_coefficients(const std::vector<Eigen::Vector3d>& q);
  // From coefficients in u = (2 t - t_lo - t_hi) / (t_hi - t_lo) (c_0 first), as the fit computes them; t_hi > t_lo.
  static PolynomialCurve from_centred_coefficients(std::vector<Eigen::Vector3d> c, double t_lo = 0.0,
                                                   double t_hi = 1.0);

  int degree() const { return static_cast<int>(centred_.size()) - 1; }
  // Q_0 .. Q_n with C(t) = sum Q_k t^k, mm.
  std::vector<Eigen::Vector3d> power_coefficients() const;

  Eigen::Vector3d position(double t) const { return derivative(t, 0); }
  // d^order C / dt^order at t (order >= 0; zero beyond the degree). Any t: outside [0, 1] it extrapolates.
  Eigen::Vector3d derivative(double t, int order = 1) const;
  double speed(double t) const { return derivative(t, 1).norm(); }

  // Signed arc length from t0 to t1, mm (arc_length.h).
  double arc_length(double t0, double t1, const ArcLengthOptions& options = {}) const;
  // The t in [t0, t1] at arc length s_mm from t0 (arc_length.h).
  ArcLengthInverse parameter_at_arc_length(double s_mm, double t0 = 0.0, double t1 = 1.0,
                                           double tolerance_mm = 1e-10) const;

 private:
  std::vector<Eigen::Vector3d> centred_;  // coefficients of u^k
  double scale_ = 2.0;                    // u = scale_ t + shift_
  double shift_ = -1.0;
};

struct PolynomialCurveOptions {
  int degree = 3;  // n, in [1, 15]

  bool IsValid(std::string* error) const;
};

struct PolynomialCurveFit {
  PolynomialCurve curve;
  bool ok = false;  // the solve had full rank and finite residuals
  std::string termination = "not run";
  std::vector<double> parameters;          // t_i, chord length / total: 0 first, 1 last
  std::vector<Eigen::Vector3d> residuals;  // P_i - C(t_i), mm
  std::vector<double> residual_mm;         // |P_i - C(t_i)|
  double rms_mm = 0.0;
  double max_residual_mm = 0.0;
  double chord_length_mm = 0.0;   // sum of |P_i - P_{i-1}|
  double condition_number = 0.0;  // of the scaled basis matrix (largest / smallest singular value)
};

// Throws conform::Error when the options are invalid, a point is not finite, all points coincide, or there are fewer
// distinct parameter values than the degree + 1 coefficients to determine (too few points, or repeated ones).
PolynomialCurveFit fit_polynomial_curve(const std::vector<Eigen::Vector3d>& points,
                                        const PolynomialCurveOptions& options);
// The same over given parameters (one finite value per point, any order) instead of chord length.
PolynomialCurveFit fit_polynomial_curve(const std::vector<Eigen::Vector3d>& points,
                                        const std::vector<double>& parameters, const PolynomialCurveOptions& options);

// t_i = chord length from the first point to P_i / total chord length. Throws conform::Error when the total is zero.
std::vector<double> chord_length_parameters(const std::vector<Eigen::Vector3d>& points);

}  // namespace conform
