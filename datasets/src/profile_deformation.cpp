#include "conform/datasets/profile_deformation.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "conform/core/error.h"

namespace conform {
namespace {

// 4-point Gauss-Legendre on [-1, 1]: exact for degree 7, plenty on a 10 mm step of a smooth frame.
constexpr double kNodes[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr double kWeights[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

// 6x^5 - 15x^4 + 10x^3 on [0, 1], clamped: C2 where the kink starts and ends.
double smootherstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * x * (x * (6.0 * x - 15.0) + 10.0);
}

}  // namespace

bool ProfileDeformationOptions::IsValid(std::string* error) const {
  std::string problem;
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!(length_mm > 0.0) || !finite(length_mm)) {
    problem = "length_mm must be positive";
  } else if (!(width_mm > 0.0) || !finite(width_mm)) {
    problem = "width_mm must be positive";
  } else if (!finite(bow_in_plane_mm) || !finite(bow_out_of_plane_mm) || !finite(twist_rad) || !finite(kink_rad)) {
    problem = "bow, twist and kink must be finite";
  } else if (!(std::abs(bow_asymmetry) <= 1.0)) {
    problem = "bow_asymmetry must be in [-1, 1]";
  } else if (kink_rad != 0.0 && !(kink_at_mm >= 0.0 && kink_at_mm <= length_mm)) {
    problem = "kink_at_mm must lie in [0, length_mm]";
  } else if (!(kink_length_mm > 0.0) || !finite(kink_length_mm)) {
    problem = "kink_length_mm must be positive";
  } else if (std::abs(kink_rad) >= 1.0) {
    problem = "|kink_rad| must be below 1 rad";
  } else if (8.0 * std::abs(bow_in_plane_mm) >= length_mm || 4.0 * std::abs(bow_out_of_plane_mm) >= length_mm) {
    problem = "the bow is too large for the length (the edge slope would reach 1)";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

ProfileDeformation::ProfileDeformation(const ProfileDeformationOptions& options) : options_(options) {
  std::string problem;
  if (!options.IsValid(&problem)) throw Error("profile deformation: " + problem);
  const int steps = std::max(1, static_cast<int>(std::ceil(options.length_mm / 10.0)));
  step_ = options.length_mm / steps;
  table_.assign(static_cast<std::size_t>(steps) + 1, Eigen::Vector3d::Zero());
  for (int k = 1; k <= steps; ++k) {
    const double a = (k - 1) * step_, h = 0.5 * step_;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int q = 0; q < 4; ++q) sum += kWeights[q] * frame(a + h * (1.0 + kNodes[q])).col(0);
    table_[static_cast<std::size_t>(k)] = table_[static_cast<std::size_t>(k) - 1] + h * sum;
  }
}

double ProfileDeformation::heading(double s) const {
  const ProfileDeformationOptions& o = options_;
  const double L = o.length_mm, u = s / L;
  // v'(s) for v = bow 4u(1-u)(1 + a(2u-1)) = bow (4(1 - a)u + 4(3a - 1)u^2 - 8a u^3)... in u; differentiated.
  const double dv_du = o.bow_in_plane_mm * (4.0 * (1.0 - o.bow_asymmetry) + 8.0 * (3.0 * o.bow_asymmetry - 1.0) * u -
                                            24.0 * o.bow_asymmetry * u * u);
  const double kink = o.kink_rad * smootherstep((s - o.kink_at_mm) / o.kink_length_mm + 0.5);
  return std::asin(dv_du / L) + kink;
}

double ProfileDeformation::pitch(double s) const {
  const double L = options_.length_mm, u = s / L;
  return std::asin(options_.bow_out_of_plane_mm * (4.0 - 8.0 * u) / L);
}

Eigen::Matrix3d ProfileDeformation::frame(double s_mm) const {
  const double s = std::clamp(s_mm, 0.0, options_.length_mm);
  const double psi = options_.twist_rad * s / options_.length_mm;
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(heading(s), Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(-pitch(s), Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  return R;
}

Eigen::Vector3d ProfileDeformation::edge(double s_mm) const {
  const double s = std::clamp(s_mm, 0.0, options_.length_mm);
  const std::size_t k = std::min(static_cast<std::size_t>(s / step_), table_.size() - 1);
  const double a = static_cast<double>(k) * step_;
  const double h = 0.5 * (s - a);
  if (!(h > 0.0)) return table_[k];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int q = 0; q < 4; ++q) sum += kWeights[q] * frame(a + h * (1.0 + kNodes[q])).col(0);
  return table_[k] + h * sum;
}

Eigen::Vector3d ProfileDeformation::map(double tx_mm, double ty_mm) const {
  return edge(ty_mm) + tx_mm * frame(ty_mm).col(1);
}

Eigen::Vector2d ProfileDeformation::straighten(const Eigen::Vector3d& p, double* off_web_mm) const {
  // (p - E(s)) . T(s) = 0: d/ds of it is -1 + (p - E) . T', close to -1 on a gently bent profile, so s += f
  // contracts by |Tx curvature| per step.
  double s = std::clamp(p.x() - table_.front().x(), 0.0, options_.length_mm);
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double f = (p - edge(s)).dot(frame(s).col(0));
    const double next = std::clamp(s + f, 0.0, options_.length_mm);
    const bool done = std::abs(next - s) < 1e-11;
    s = next;
    if (done) break;
  }
  const Eigen::Matrix3d R = frame(s);
  const Eigen::Vector3d d = p - edge(s);
  if (off_web_mm != nullptr) *off_web_mm = d.dot(R.col(2));
  return {d.dot(R.col(1)), s};
}

}  // namespace conform
