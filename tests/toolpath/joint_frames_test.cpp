#include "conform/toolpath/intersection/joint_frames.h"

#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/constants.h"

namespace conform {
namespace {

constexpr double kTol = 1e-12;

TEST(JointFrames, RightAngleJointPutsTheStubOnTheXAxisPointingAtTheLeg) {
  TubeJointSpec spec;  // pitch pi/2
  spec.offset_mm = 120.0;
  spec.protrusion_mm = 1500.0;
  const Eigen::Isometry3d T = T_L_S(spec);
  // Distal end at protrusion along +x_L, offset along y_L; the stub's z points back at the leg.
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1500.0, 120.0, 0.0), kTol)) << T.translation().transpose();
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitX(), kTol));
  // x_S (towards the toe) runs along the leg axis, y_S along y_L.
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitZ(), kTol));
  EXPECT_TRUE((T.linear() * Eigen::Vector3d::UnitY()).isApprox(Eigen::Vector3d::UnitY(), kTol));
}

TEST(JointFrames, PitchIsTheAngleBetweenTheAxesAndTheOffsetTheirDistance) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pitch(0.05, kPi / 2);
  std::uniform_real_distribution<double> length(-800.0, 800.0);
  for (int trial = 0; trial < 100; ++trial) {
    TubeJointSpec spec;
    spec.pitch_rad = pitch(rng);
    spec.offset_mm = length(rng);
    spec.protrusion_mm = std::abs(length(rng)) + 1000.0;
    const Eigen::Isometry3d T = T_L_S(spec);
    const Eigen::Vector3d stub_axis = T.linear() * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR(std::acos(stub_axis.dot(Eigen::Vector3d::UnitZ())), spec.pitch_rad, 1e-9);
    // The stub axis is perpendicular to y_L (x_L-z_L plane = the plane through the leg axis parallel to it) and
    // the common perpendicular of the two axes is y_L, so their distance is |offset|.
    EXPECT_NEAR(stub_axis.y(), 0.0, kTol);
    EXPECT_NEAR(T.translation().y(), spec.offset_mm, 1e-9);
    // The stub comes from +x_L and its z points towards the leg.
    EXPECT_GT(T.translation().x(), 0.0);
    EXPECT_LT(stub_axis.x(), 0.0);
    // Going back the protrusion along the stub axis from the distal end reaches the leg axis's closest point.
    EXPECT_TRUE(
        (T * Eigen::Vector3d(0.0, 0.0, spec.protrusion_mm)).isApprox(Eigen::Vector3d(0.0, spec.offset_mm, 0.0), 1e-12))
        << trial;
    EXPECT_NEAR(T.linear().determinant(), 1.0, kTol);
  }
}

TEST(JointFrames, PaperFrameSitsOnTheStubAxisClosestToTheLegAxisAndPointsAway) {
  TubeJointSpec spec;
  spec.pitch_rad = kPi / 4;
  spec.offset_mm = -75.0;
  spec.protrusion_mm = 900.0;
  const Eigen::Isometry3d T = T_L_P(spec);
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(0.0, -75.0, 0.0), kTol)) << T.translation().transpose();
  EXPECT_NEAR(T.linear().determinant(), 1.0, kTol);
  // z_P = -z_S (away from the leg), y_P = x_S (the toe), x_P = y_S.
  const Eigen::Isometry3d S = T_L_S(spec);
  EXPECT_TRUE(T.linear().col(2).isApprox(-S.linear().col(2), kTol));
  EXPECT_TRUE(T.linear().col(1).isApprox(S.linear().col(0), kTol));
  EXPECT_TRUE(T.linear().col(0).isApprox(S.linear().col(1), kTol));
  // The pipe azimuth phi of S (from x_S to y_S) is the paper's theta: (r cos phi, r sin phi) in S is
  // (r sin phi, r cos phi) in P.
  const double phi = 0.7;
  const Eigen::Vector3d p_S(150.0 * std::cos(phi), 150.0 * std::sin(phi), 42.0);
  const Eigen::Vector3d p_P = T_S_P(spec).inverse() * p_S;
  EXPECT_NEAR(p_P.x(), 150.0 * std::sin(phi), kTol);
  EXPECT_NEAR(p_P.y(), 150.0 * std::cos(phi), kTol);
}

TEST(JointFrames, RightAnglePitchHasExactCosineAndSine) {
  const Eigen::Vector2d cs = pitch_cos_sin(90.0 / 180.0 * kPi);
  EXPECT_EQ(cs.x(), 0.0);
  EXPECT_EQ(cs.y(), 1.0);
  const Eigen::Vector2d cs30 = pitch_cos_sin(kPi / 6);
  EXPECT_NEAR(cs30.x(), std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(cs30.y(), 0.5, 1e-15);
}

TEST(JointFrames, SpecValidationNamesThePitch) {
  std::string error;
  TubeJointSpec spec;
  EXPECT_TRUE(spec.IsValid(&error)) << error;
  spec.pitch_rad = 0.0;
  EXPECT_FALSE(spec.IsValid(&error));
  EXPECT_NE(error.find("pitch"), std::string::npos) << error;
  spec.pitch_rad = kPi / 2 + 1e-9;
  EXPECT_FALSE(spec.IsValid(nullptr));
  spec.pitch_rad = kPi / 3;
  spec.offset_mm = std::nan("");
  EXPECT_FALSE(spec.IsValid(&error));
  EXPECT_NE(error.find("finite"), std::string::npos) << error;
}

}  // namespace
}  // namespace conform
