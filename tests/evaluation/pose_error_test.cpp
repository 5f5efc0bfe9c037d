#include "conform/evaluation/pose_error.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/constants.h"

namespace conform {
namespace {

Eigen::Isometry3d pose(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.translation() = t;
  return T;
}

TEST(PoseError, KnownRelativeRotationAndTranslation) {
  const Eigen::Isometry3d a = pose(0.7, {1, 2, 3}, {10, -5, 2});
  // b = a followed by 30 deg about some axis in a's frame, and moved by (3, 4, 12) mm (length 13).
  Eigen::Isometry3d b = a * pose(kPi / 6, {-2, 1, 0.5}, Eigen::Vector3d::Zero());
  b.translation() = a.translation() + Eigen::Vector3d(3, 4, 12);
  const PoseError e = pose_error(a, b);
  EXPECT_NEAR(e.rotation_rad, kPi / 6, 1e-14);
  EXPECT_NEAR(e.translation_mm, 13.0, 1e-13);
  const PoseError back = pose_error(b, a);
  EXPECT_EQ(back.rotation_rad, e.rotation_rad);
  EXPECT_EQ(back.translation_mm, e.translation_mm);
}

TEST(PoseError, IdenticalPosesHaveNoError) {
  const Eigen::Isometry3d a = pose(2.0, {0, 1, 1}, {1, 2, 3});
  const PoseError e = pose_error(a, a);
  EXPECT_NEAR(e.rotation_rad, 0.0, 1e-15);
  EXPECT_EQ(e.translation_mm, 0.0);
}

TEST(PoseError, SmallAndHalfTurnAnglesKeepTheirDigits) {
  const Eigen::Isometry3d a = pose(0.3, {0, 0, 1}, {0, 0, 0});
  for (double angle : {1e-9, 1e-6, 1e-3}) {
    const PoseError e = pose_error(a, a * pose(angle, {1, 1, 0}, {0, 0, 0}));
    EXPECT_NEAR(e.rotation_rad, angle, angle * 1e-6) << angle;  // acos of the trace would give 0 for 1e-9
  }
  const PoseError half = pose_error(Eigen::Isometry3d::Identity(), pose(kPi, {0, 1, 0}, {0, 0, 0}));
  EXPECT_NEAR(half.rotation_rad, kPi, 1e-12);
  const PoseError almost = pose_error(Eigen::Isometry3d::Identity(), pose(kPi - 1e-4, {3, 1, 0}, {0, 0, 0}));
  EXPECT_NEAR(almost.rotation_rad, kPi - 1e-4, 1e-12);
}

}  // namespace
}  // namespace conform
