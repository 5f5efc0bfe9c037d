#include "conform/fitting/polynomial_curve.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr int kMaxDegree = 15;
// Beyond this condition number of the scaled basis the coefficients would carry less than ~3 correct digits.
constexpr double kMaxCondition = 1e13;

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * static_cast<double>(n - k + i) / static_cast<double>(i);
  return b;
}

// k (k - 1) ... (k - r + 1)
double falling(int k, int r) {
  double f = 1.0;
  for (int i = 0; i < r; ++i) f *= static_cast<double>(k - i);
  return f;
}

std::size_t distinct_count(const std::vector<double>& sorted) {
  std::size_t count = sorted.empty() ? 0 : 1;
  for (std::size_t i = 1; i < sorted.size(); ++i) count += sorted[i] != sorted[i - 1] ? 1 : 0;
  return count;
}

void check_count(std::size_t points, int degree) {
  if (points < static_cast<std::size_t>(degree + 1)) {
    throw Error("fit_polynomial_curve: " + std::to_string(points) + " points for a degree " + std::to_string(degree) +
                " curve, which has " + std::to_string(degree + 1) + " coefficients per coordinate");
  }
}

void check_points(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& parameters, int degree) {
  const auto columns = static_cast<std::size_t>(degree + 1);
  if (parameters.size() != points.size()) {
    throw Error("fit_polynomial_curve: " + std::to_string(parameters.size()) + " parameters for " +
                std::to_string(points.size()) + " points");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error("fit_polynomial_curve: point " + std::to_string(i) + " is not finite");
    if (!std::isfinite(parameters[i])) {
      throw Error("fit_polynomial_curve: parameter " + std::to_string(i) + " is not finite");
    }
  }
  check_count(points.size(), degree);
  std::vector<double> sorted = parameters;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t distinct = distinct_count(sorted);
  if (distinct < columns) {
    throw Error("fit_polynomial_curve: the points give only " + std::to_string(distinct) +
                " distinct positions along the curve; degree " + std::to_string(degree) + " needs " +
                std::to_string(columns));
  }
}

struct Solve {
  PolynomialCurve curve;
  double condition_number = 0.0;
};

// Householder QR of the column-scaled basis in u (see the header); the singular values of R are those of the basis.
Solve solve_least_squares(const std::vector<Eigen::Vector3d>& points, const std::vector<double>& t, int degree,
                          double t_lo, double t_hi) {
  const int columns = degree + 1;
  const auto rows = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd basis(rows, columns);
  Eigen::MatrixXd rhs(rows, 3);
  for (Eigen::Index i = 0; i < rows; ++i) {
    const double u = (2.0 * t[static_cast<std::size_t>(i)] - t_lo - t_hi) / (t_hi - t_lo);
    double power = 1.0;
    for (int k = 0; k < columns; ++k, power *= u) basis(i, k) = power;
    rhs.row(i) = points[static_cast<std::size_t>(i)].transpose();
  }
  const Eigen::VectorXd scale = basis.colwise().norm().cwiseInverse().transpose();
  basis = basis * scale.asDiagonal();
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(basis);
  const Eigen::MatrixXd r = qr.matrixQR().topRows(columns).triangularView<Eigen::Upper>();
  const Eigen::VectorXd singular = Eigen::JacobiSVD<Eigen::MatrixXd>(r).singularValues();
  Solve out;
  out.condition_number = singular(0) / singular(columns - 1);
  if (!(out.condition_number < kMaxCondition)) {
    throw Error("fit_polynomial_curve: the basis is numerically singular (condition number " +
                std::to_string(out.condition_number) + "): too high a degree for the points' spread along the curve");
  }
  const Eigen::MatrixXd y = scale.asDiagonal() * qr.solve(rhs);
  std::vector<Eigen::Vector3d> c(static_cast<std::size_t>(columns));
  for (int k = 0; k < columns; ++k) c[static_cast<std::size_t>(k)] = y.row(k).transpose();
  out.curve = PolynomialCurve::from_centred_coefficients(std::move(c), t_lo, t_hi);
  return out;
}

}  // namespace

PolynomialCurve PolynomialCurve::from_centred_coefficients(std::vector<Eigen::Vector3d> c, double t_lo, double t_hi) {
  if (c.empty()) throw Error("polynomial curve: no coefficients");
  if (!(std::isfinite(t_lo) && std::isfinite(t_hi) && t_hi > t_lo)) {
    throw Error("polynomial curve: the parameter range must be finite with t_hi > t_lo");
  }
  PolynomialCurve curve;
  curve.centred_ = std::move(c);
  curve.scale_ = 2.0 / (t_hi - t_lo);
  curve.shift_ = -(t_lo + t_hi) / (t_hi - t_lo);
  return curve;
}

// On [0, 1], t = (u + 1) / 2, so Q_k t^k = Q_k 2^-k sum_j binom(k, j) u^j.
PolynomialCurve PolynomialCurve::from_power_coefficients(const std::vector<Eigen::Vector3d>& q) {
  if (q.empty()) throw Error("polynomial curve: no coefficients");
  std::vector<Eigen::Vector3d> c(q.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < q.size(); ++k) {
    if (!q[k].allFinite()) throw Error("polynomial curve: coefficient " + std::to_string(k) + " is not finite");
    const double scale = std::ldexp(1.0, -static_cast<int>(k));
    for (std::size_t j = 0; j <= k; ++j) {
      c[j] += scale * binomial(static_cast<int>(k), static_cast<int>(j)) * q[k];
    }
  }
  return from_centred_coefficients(std::move(c));
}

// u = a t + b, so c_k u^k = c_k sum_j binom(k, j) a^j b^(k - j) t^j.
std::vector<Eigen::Vector3d> PolynomialCurve::power_coefficients() const {
  std::vector<Eigen::Vector3d> q(centred_.size(), Eigen::Vector3d::Zero());
  for (std::size_t k = 0; k < centred_.size(); ++k) {
    for (std::size_t j = 0; j <= k; ++j) {
      const double factor = binomial(static_cast<int>(k), static_cast<int>(j)) *
                            std::pow(scale_, static_cast<double>(j)) * std::pow(shift_, static_cast<double>(k - j));
      q[j] += factor * centred_[k];
    }
  }
  return q;
}

// Horner's rule on the order-th derivative in u, times (du/dt)^order.
Eigen::Vector3d PolynomialCurve::derivative(double t, int order) const {
  if (order < 0) throw Error("polynomial curve: derivative order must be >= 0");
  const int n = degree();
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  if (order > n) return value;
  const double u = scale_ * t + shift_;
  for (int k = n; k >= order; --k) value = value * u + falling(k, order) * centred_[static_cast<std::size_t>(k)];
  // The chain rule's scale^order; the first two orders multiplied out (pow's cost on every speed evaluation).
  const double factor = order == 0 ? 1.0 : order == 1 ? scale_ : order == 2 ? scale_ * scale_
                                                                             : std::pow(scale_, static_cast<double>(order));
  return factor * value;
}

double PolynomialCurve::arc_length(double t0, double t1, const ArcLengthOptions& options) const {
  return conform::arc_length([this](double t) { return speed(t); }, t0, t1, options);
}

ArcLengthInverse PolynomialCurve::parameter_at_arc_length(double s_mm, double t0, double t1,
                                                          double tolerance_mm) const {
  return conform::parameter_at_arc_length([this](double t) { return speed(t); }, t0, t1, s_mm, tolerance_mm);
}

bool PolynomialCurveOptions::IsValid(std::string* error) const {
  if (degree < 1 || degree > kMaxDegree) {
    if (error != nullptr) *error = "degree must be in [1, 15], got " + std::to_string(degree);
    return false;
  }
  return true;
}

std::vector<double> chord_length_parameters(const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> t(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) t[i] = t[i - 1] + (points[i] - points[i - 1]).norm();
  const double total = points.empty() ? 0.0 : t.back();
  if (!(total > 0.0)) throw Error("chord-length parameters: all " + std::to_string(points.size()) + " points coincide");
  for (double& v : t) v /= total;
  t.back() = 1.0;
  return t;
}

PolynomialCurveFit fit_polynomial_curve(const std::vector<Eigen::Vector3d>& points,
                                        const PolynomialCurveOptions& options) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error("fit_polynomial_curve: point " + std::to_string(i) + " is not finite");
  }
  std::string why;
  if (!options.IsValid(&why)) throw Error("fit_polynomial_curve: " + why);
  check_count(points.size(), options.degree);
  return fit_polynomial_curve(points, chord_length_parameters(points), options);  // throws when all coincide
}

PolynomialCurveFit fit_polynomial_curve(const std::vector<Eigen::Vector3d>& points,
                                        const std::vector<double>& parameters, const PolynomialCurveOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("fit_polynomial_curve: " + why);
  check_points(points, parameters, options.degree);
  PolynomialCurveFit fit;
  fit.parameters = parameters;
  const auto [t_lo, t_hi] = std::minmax_element(parameters.begin(), parameters.end());
  const Solve solved = solve_least_squares(points, parameters, options.degree, *t_lo, *t_hi);
  fit.condition_number = solved.condition_number;
  fit.curve = solved.curve;

  double sum_squares = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    fit.residuals.push_back(points[i] - fit.curve.position(fit.parameters[i]));
    fit.residual_mm.push_back(fit.residuals.back().norm());
    sum_squares += fit.residual_mm.back() * fit.residual_mm.back();
    fit.max_residual_mm = std::max(fit.max_residual_mm, fit.residual_mm.back());
    fit.chord_length_mm += i > 0 ? (points[i] - points[i - 1]).norm() : 0.0;
  }
  fit.rms_mm = std::sqrt(sum_squares / static_cast<double>(points.size()));
  fit.ok = std::isfinite(fit.rms_mm);
  fit.termination = fit.ok ? "ok" : "non-finite residuals";
  return fit;
}

}  // namespace conform
