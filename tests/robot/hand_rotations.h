#pragma once
// Rotations written out by hand from the vendors' definitions, for the tests of the program writers and their angle
// conventions (robot_program_test.cpp, robot_angles_test.cpp): not the writers' own conversions.

#include <cmath>

#include <Eigen/Geometry>

#include "conform/core/constants.h"

namespace conform::test {

constexpr double kAxisTol = 1e-9;  // rad

inline double rad(double deg) { return deg * kPi / 180.0; }

// Elementary rotations, written out (right-handed, active).
inline Eigen::Matrix3d Rx(double a) {
  Eigen::Matrix3d m;
  m << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return m;
}
inline Eigen::Matrix3d Ry(double a) {
  Eigen::Matrix3d m;
  m << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return m;
}
inline Eigen::Matrix3d Rz(double a) {
  Eigen::Matrix3d m;
  m << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return m;
}

// Unit quaternion (w, x, y, z) -> matrix (ABB's orient, w = q1).
inline Eigen::Matrix3d from_quaternion(double w, double x, double y, double z) {
  Eigen::Matrix3d m;
  m << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return m;
}

// Rodrigues: rotation vector (UR) -> matrix.
inline Eigen::Matrix3d from_rotation_vector(const Eigen::Vector3d& v) {
  const double a = v.norm();
  if (a == 0.0) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d k = v / a;
  Eigen::Matrix3d K;
  K << 0, -k.z(), k.y(), k.z(), 0, -k.x(), -k.y(), k.x(), 0;
  return Eigen::Matrix3d::Identity() + std::sin(a) * K + (1 - std::cos(a)) * K * K;
}

inline double angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::AngleAxisd d(a.transpose() * b);
  return std::abs(d.angle());
}

}  // namespace conform::test
