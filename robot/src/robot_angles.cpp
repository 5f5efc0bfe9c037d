#include "conform/robot/robot_angles.h"

#include <cmath>

#include <Eigen/Geometry>

#include "conform/core/constants.h"

namespace conform {
namespace {

// Below this cos(B) the first angle is not defined by the matrix (gimbal lock); above it, the third angle is solved
// from the first two so that the three compose to the matrix exactly, whatever the conditioning of the first.
constexpr double kLock = 1e-12;

double deg(double rad) { return rad * 180.0 / kPi; }
double rad(double deg) { return deg * kPi / 180.0; }

// `angle` plus whole turns, in (-180, 180]: the range the controllers take (KRL A and C, FANUC W and R, VAL3 rx and
// rz); their orientation interpolation is on the rotation, so a step across +-180 is not a turn of the wrist.
double wrap_deg(double angle) {
  const double wrapped = angle - 360.0 * std::floor((angle + 180.0) / 360.0);  // [-180, 180)
  return wrapped == -180.0 ? 180.0 : wrapped;
}

Eigen::Matrix3d rx(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d ry(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d rz(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

}  // namespace

Eigen::Vector3d euler_zyx_deg(const Eigen::Matrix3d& r, const Eigen::Vector3d* previous) {
  const double cos_b = std::hypot(r(0, 0), r(1, 0));
  const double b = std::atan2(-r(2, 0), cos_b);
  double a = cos_b > kLock ? std::atan2(r(1, 0), r(0, 0)) : (previous != nullptr ? rad((*previous)(0)) : 0.0);
  const Eigen::Matrix3d m = ry(b).transpose() * rz(a).transpose() * r;  // = Rx(C)
  const double c = std::atan2(m(2, 1), m(1, 1));
  return Eigen::Vector3d(wrap_deg(deg(a)), deg(b), wrap_deg(deg(c)));
}

Eigen::Vector3d euler_xyz_deg(const Eigen::Matrix3d& r, const Eigen::Vector3d* previous) {
  const double cos_b = std::hypot(r(1, 2), r(2, 2));
  const double b = std::atan2(r(0, 2), cos_b);
  double a = cos_b > kLock ? std::atan2(-r(1, 2), r(2, 2)) : (previous != nullptr ? rad((*previous)(0)) : 0.0);
  const Eigen::Matrix3d m = ry(b).transpose() * rx(a).transpose() * r;  // = Rz(c)
  const double c = std::atan2(m(1, 0), m(0, 0));
  return Eigen::Vector3d(wrap_deg(deg(a)), deg(b), wrap_deg(deg(c)));
}

Eigen::Vector4d quaternion_wxyz(const Eigen::Matrix3d& r, const Eigen::Vector4d* previous) {
  Eigen::Quaterniond q(r);
  q.normalize();
  Eigen::Vector4d out(q.w(), q.x(), q.y(), q.z());
  const bool flip = previous != nullptr ? out.dot(*previous) < 0.0 : out(0) < 0.0;
  return flip ? Eigen::Vector4d(-out) : out;
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& r, const Eigen::Vector3d* previous) {
  const Eigen::AngleAxisd aa{Eigen::Quaterniond(r).normalized()};
  double angle = aa.angle();
  Eigen::Vector3d axis = aa.axis();
  if (angle > kPi) {  // Eigen may give (0, 2 pi): the same rotation as 2 pi - angle about -axis
    angle = 2.0 * kPi - angle;
    axis = -axis;
  }
  const Eigen::Vector3d v = angle * axis;
  if (previous == nullptr) return v;
  const Eigen::Vector3d other = (angle - 2.0 * kPi) * axis;
  return (other - *previous).norm() < (v - *previous).norm() ? other : v;
}

}  // namespace conform
