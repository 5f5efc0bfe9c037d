#include "convergence.h"

#include <cmath>
#include <limits>

namespace conform::detail {

namespace {

// Consecutive steps this aligned (cosine in the metric of (1)) are one motion still under way, not a cycle.
constexpr double kSameWay = 0.9;

}  // namespace

Vector6d scaled_twist(const Eigen::Isometry3d& delta, const Eigen::Vector3d& centre, double length_scale_mm) {
  const Eigen::AngleAxisd rotation(delta.linear());
  Vector6d x;
  x.head<3>() = rotation.angle() * rotation.axis() * length_scale_mm;
  x.tail<3>() = delta * centre - centre;
  return x;
}

Eigen::Isometry3d scaled_motion(const Eigen::Isometry3d& delta, const Eigen::Vector3d& centre, double factor) {
  const Eigen::AngleAxisd rotation(delta.linear());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(factor * rotation.angle(), rotation.axis()).toRotationMatrix();
  out.translation() = centre + factor * (delta * centre - centre) - out.linear() * centre;
  return out;
}

bool ConvergenceTest::converged(const Eigen::Isometry3d& delta, const PlaneNormalMatrix& plane, double noise_mm) {
  const Eigen::Vector3d& c = plane.centre;
  const double rotation = Eigen::AngleAxisd(delta.linear()).angle();
  const bool below_floor = rotation <= rotation_tolerance_rad_ && (delta * c - c).norm() <= translation_tolerance_mm_;
  const Eigen::Isometry3d previous = previous_;
  const bool had_previous = has_previous_;
  previous_ = delta;
  has_previous_ = true;
  creeping_ = false;
  const double jumped_rho = jumped_rho_;
  jumped_rho_ = -1.0;
  if (!(noise_mm > 0.0) || !(plane.length_scale_mm > 0.0) || plane.count == 0) return below_floor;
  // Eq. (1): the metric N H / sigma^2 on scaled twists.
  const Matrix6d metric = static_cast<double>(plane.count) * plane.H / (noise_mm * noise_mm);
  const Vector6d x = scaled_twist(delta, c, plane.length_scale_mm);
  last_m_ = std::sqrt(std::max(0.0, x.dot(metric * x)));
  double still_to_come = 0.0;
  if (jumped_rho >= 0.0) {
    still_to_come = last_m_ * jumped_rho / (1.0 - jumped_rho);
  } else if (had_previous) {
    const Vector6d y = scaled_twist(previous, c, plane.length_scale_mm);
    const double m_previous = std::sqrt(std::max(0.0, y.dot(metric * y)));
    const double cosine = m_previous > 0.0 && last_m_ > 0.0 ? x.dot(metric * y) / (last_m_ * m_previous) : 0.0;
    if (cosine > kSameWay) {
      const double rho = last_m_ / m_previous;
      creeping_ = rho < 1.0;
      rho_ = rho;
      still_to_come = rho < 1.0 ? last_m_ * rho / (1.0 - rho) : std::numeric_limits<double>::infinity();
    }
  }
  return below_floor || last_m_ + still_to_come <= fraction_;
}

}  // namespace conform::detail
