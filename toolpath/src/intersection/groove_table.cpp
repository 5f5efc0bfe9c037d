#include "conform/toolpath/intersection/groove_table.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "conform/core/constants.h"

namespace conform {
namespace {

}  // namespace

GrooveTable::GrooveTable(std::vector<std::pair<double, double>> rows, GrooveInterpolation interpolation)
    : rows_(std::move(rows)), interpolation_(interpolation) {
  prepare();
}

GrooveTable GrooveTable::quarters(double toe, double side1, double heel, double side2,
                                  GrooveInterpolation interpolation) {
  return GrooveTable({{0.0, toe}, {kPi / 2, side1}, {kPi, heel}, {1.5 * kPi, side2}}, interpolation);
}

void GrooveTable::prepare() {
  phi_.clear();
  alpha_.clear();
  for (const auto& [phi, alpha] : rows_) {
    if (phi >= kTwoPi && !phi_.empty()) continue;  // the paper's closing row
    phi_.push_back(phi);
    alpha_.push_back(alpha);
  }
  second_.assign(phi_.size(), 0.0);
  const std::size_t m = phi_.size();
  if (interpolation_ != GrooveInterpolation::kSpline || m < 3) return;
  // Periodic cubic spline: h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (s_i - s_{i-1}), cyclic.
  const auto h = [&](std::size_t i) { return i + 1 < m ? phi_[i + 1] - phi_[i] : phi_[0] + kTwoPi - phi_[m - 1]; };
  const auto slope = [&](std::size_t i) { return (alpha_[(i + 1) % m] - alpha_[i]) / h(i); };
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(m));
  Eigen::VectorXd b(static_cast<Eigen::Index>(m));
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t before = (i + m - 1) % m;
    const auto r = static_cast<Eigen::Index>(i);
    A(r, static_cast<Eigen::Index>(before)) += h(before);
    A(r, r) += 2.0 * (h(before) + h(i));
    A(r, static_cast<Eigen::Index>((i + 1) % m)) += h(i);
    b(r) = 6.0 * (slope(i) - slope(before));
  }
  const Eigen::VectorXd M = A.partialPivLu().solve(b);
  for (std::size_t i = 0; i < m; ++i) second_[i] = M(static_cast<Eigen::Index>(i));
}

bool GrooveTable::IsValid(std::string* error) const {
  std::ostringstream why;
  const double deg = 180.0 / kPi;
  for (std::size_t i = 0; i < rows_.size() && why.tellp() == 0; ++i) {
    const auto& [phi, alpha] = rows_[i];
    if (!std::isfinite(phi) || phi < 0.0 || phi > kTwoPi + 1e-12) {
      why << "groove row " << i + 1 << ": azimuth " << phi * deg << " deg is outside [0, 360]";
    } else if (!std::isfinite(alpha) || alpha < 0.0 || alpha >= kPi / 2) {
      why << "groove row " << i + 1 << ": angle " << alpha * deg << " deg is outside [0, 90) (a negative groove "
          << "angle would cut into the leg side of the joint)";
    } else if (i > 0 && !(phi > rows_[i - 1].first)) {
      why << "groove row " << i + 1 << ": azimuth " << phi * deg << " deg does not increase";
    } else if (phi >= kTwoPi - 1e-12 && i > 0 && (rows_[0].first != 0.0 || alpha != rows_[0].second)) {
      why << "groove row " << i + 1 << " at 360 deg must close the table: the first row at 0 deg with the same angle";
    }
  }
  if (why.tellp() == 0 && phi_.empty()) why << "the groove table has no rows";
  if (why.tellp() == 0 && interpolation_ == GrooveInterpolation::kSpline && phi_.size() < 3) {
    why << "a periodic spline needs >= 3 groove rows in [0, 360) deg";
  }
  for (int k = 0; k < 3600 && why.tellp() == 0; ++k) {
    const double a = at(kTwoPi * k / 3600.0);
    if (!(a >= 0.0 && a < kPi / 2)) {
      why << "the interpolated groove angle is " << a * deg << " deg at azimuth " << k / 10.0
          << " deg, outside [0, 90): the spline overshoots between rows; add rows or use linear";
    }
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

double GrooveTable::at(double phi_rad) const {
  if (phi_.empty()) return 0.0;
  double phi = std::fmod(phi_rad, kTwoPi);
  if (phi < 0.0) phi += kTwoPi;
  const std::size_t m = phi_.size();
  // The span [phi_i, phi_{i+1}) holding phi, cyclically (before the first node: the closing span).
  std::size_t i = static_cast<std::size_t>(std::upper_bound(phi_.begin(), phi_.end(), phi) - phi_.begin());
  i = i == 0 ? m - 1 : i - 1;
  const double x0 = phi_[i];
  double x1 = i + 1 < m ? phi_[i + 1] : phi_[0] + kTwoPi;
  if (phi < x0) phi += kTwoPi;
  if (m == 1) return alpha_[0];
  const double h = x1 - x0;
  const double y0 = alpha_[i];
  const double y1 = alpha_[(i + 1) % m];
  double u = (phi - x0) / h;
  switch (interpolation_) {
    case GrooveInterpolation::kLinear:
      return y0 + (y1 - y0) * u;
    case GrooveInterpolation::kQuadratic:
      u = u < 0.5 ? 2.0 * u * u : 1.0 - 2.0 * (1.0 - u) * (1.0 - u);
      return y0 + (y1 - y0) * u;
    case GrooveInterpolation::kSpline: {
      const double M0 = second_[i];
      const double M1 = second_[(i + 1) % m];
      const double a = x1 - phi;
      const double b = phi - x0;
      return M0 * a * a * a / (6.0 * h) + M1 * b * b * b / (6.0 * h) + (y0 / h - M0 * h / 6.0) * a +
             (y1 / h - M1 * h / 6.0) * b;
    }
  }
  return y0;
}

}  // namespace conform
