// The angle conventions of the robot controllers (robot/robot_angles.h): Euler angles in the controllers' range,
// gimbal lock, quaternion and rotation-vector continuity, checked against rotations written out by hand
// (hand_rotations.h). Axes to 1e-9 rad.

#include <cmath>

#include <gtest/gtest.h>

#include "conform/robot/robot_angles.h"
#include "hand_rotations.h"

namespace conform {
namespace {

using namespace test;  // hand_rotations.h

TEST(RobotAngles, EulerAnglesStayInTheControllersRangeThroughPlusMinus180) {
  // A turn about z from 170 to 190 deg and back: A stays in (-180, 180] (it steps from 180 to -179), the rotation it
  // composes moves on smoothly, and so does the quaternion.
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  Eigen::Vector4d q = Eigen::Vector4d::Zero();
  int wrapped = 0;
  for (int i = 0; i <= 40; ++i) {
    const double a = rad(170.0 + (i <= 20 ? i : 40 - i));
    const Eigen::Matrix3d r = Rz(a) * Rx(rad(179.5 + 0.05 * i));
    const Eigen::Vector3d before = abc;
    const Eigen::Vector4d q_before = q;
    abc = euler_zyx_deg(r, i == 0 ? nullptr : &abc);
    q = quaternion_wxyz(r, i == 0 ? nullptr : &q);
    for (int k : {0, 2}) EXPECT_TRUE(abc(k) > -180.0 && abc(k) <= 180.0) << i;
    if (i > 0) {
      for (int k = 0; k < 3; ++k) {
        const double step = std::abs(abc(k) - before(k));
        EXPECT_LT(std::min(step, std::abs(step - 360.0)), 1.5) << i;  // smooth but for whole turns
        wrapped += step > 180.0;
      }
      EXPECT_LT((q - q_before).norm(), 0.02) << i;
    }
    EXPECT_LT(angle_between(Rz(rad(abc(0))) * Ry(rad(abc(1))) * Rx(rad(abc(2))), r), kAxisTol);
  }
  EXPECT_GT(wrapped, 0);  // the path does cross +-180
}

TEST(RobotAngles, GimbalLockKeepsTheFirstAngleAndComposesExactly) {
  const Eigen::Matrix3d r = Rz(rad(30)) * Ry(kPi / 2) * Rx(rad(10));
  const Eigen::Vector3d abc = euler_zyx_deg(r, nullptr);
  EXPECT_NEAR(abc(0), 0.0, 1e-9);
  EXPECT_NEAR(abc(1), 90.0, 1e-6);
  EXPECT_NEAR(abc(2), -20.0, 1e-9);  // only C - A is defined at B = 90
  const Eigen::Vector3d prev(30, 89, 10);
  const Eigen::Vector3d kept = euler_zyx_deg(r, &prev);
  EXPECT_NEAR(kept(0), 30.0, 1e-9);
  EXPECT_NEAR(kept(2), 10.0, 1e-9);
  const Eigen::Vector3d xyz = euler_xyz_deg(Rx(rad(15)) * Ry(-kPi / 2) * Rz(rad(5)), nullptr);
  EXPECT_LT(angle_between(Rx(rad(xyz(0))) * Ry(rad(xyz(1))) * Rz(rad(xyz(2))), Rx(rad(15)) * Ry(-kPi / 2) * Rz(rad(5))),
            kAxisTol);
}

TEST(RobotAngles, StableApproachingGimbalLock) {
  // B -> 90 deg with A = 30, C = 10: the angles stay put (the matrix still defines them down to cos B ~ 1e-12, and
  // at the lock A is held), and compose to the frame within 1e-9 rad all the way.
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  for (int k = 0; k <= 14; ++k) {
    const double delta = k == 14 ? 0.0 : std::pow(10.0, -k);
    const Eigen::Matrix3d r = Rz(rad(30)) * Ry(kPi / 2 - delta) * Rx(rad(10));
    abc = euler_zyx_deg(r, k == 0 ? nullptr : &abc);
    EXPECT_NEAR(abc(0), 30.0, 1e-2) << delta;
    EXPECT_NEAR(abc(2), 10.0, 1e-2) << delta;
    EXPECT_LT(angle_between(Rz(rad(abc(0))) * Ry(rad(abc(1))) * Rx(rad(abc(2))), r), kAxisTol) << delta;
  }
}

TEST(RobotAngles, RotationVectorNearPiStaysOnOneSide) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int i = 0; i <= 10; ++i) {
    const double a = kPi - 0.01 + 0.002 * i;  // passes through pi
    const Eigen::Matrix3d r = from_rotation_vector(a * Eigen::Vector3d(0, 0.6, 0.8));
    const Eigen::Vector3d before = v;
    v = rotation_vector(r, i == 0 ? nullptr : &v);
    if (i > 0) {
      EXPECT_LT((v - before).norm(), 0.01) << i;
    }
    EXPECT_LT(angle_between(from_rotation_vector(v), r), kAxisTol);
  }
}

}  // namespace
}  // namespace conform
