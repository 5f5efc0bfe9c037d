#include "conform/registration/horn.h"

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "registration_test_util.h"

namespace conform {
namespace {

std::vector<Eigen::Vector3d> random_points(Random& random, int n, double size) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    points.emplace_back(random.uniform(-size, size), random.uniform(-size, size), random.uniform(-size, size));
  }
  return points;
}

TEST(Horn, RecoversAnExactTransformInBothDirections) {
  Random random(3);
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<Eigen::Vector3d> scan = random_points(random, 3 + trial, 500.0);
    // Far from the origin and up to 180 degrees, so that centring and the quaternion's sign both matter.
    const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 2000.0, {1000.0, -500.0, 300.0});
    const std::vector<Eigen::Vector3d> ref = test::transformed_points(scan, truth);
    const HornResult forward = horn_transform(scan, ref);
    ASSERT_TRUE(forward.well_posed);
    EXPECT_LT(test::rotation_error_deg(forward.T_ref_scan, truth), 1e-9);
    EXPECT_LT(test::translation_error_mm(forward.T_ref_scan, truth), 1e-8);
    const HornResult backward = horn_transform(ref, scan);
    EXPECT_LT(test::rotation_error_deg(backward.T_ref_scan, truth.inverse()), 1e-9);
    EXPECT_LT(test::translation_error_mm(backward.T_ref_scan, truth.inverse()), 1e-8);
  }
}

TEST(Horn, ZeroWeightsIgnorePairs) {
  Random random(5);
  std::vector<Eigen::Vector3d> scan = random_points(random, 10, 100.0);
  const Eigen::Isometry3d truth = test::random_motion(random, 1.0, 50.0, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> ref = test::transformed_points(scan, truth);
  std::vector<double> weights(10, 1.0);
  ref[3] += Eigen::Vector3d(40.0, -30.0, 20.0);  // a gross outlier, weighted out
  weights[3] = 0.0;
  const HornResult r = horn_transform(scan, ref, weights);
  EXPECT_LT(test::rotation_error_deg(r.T_ref_scan, truth), 1e-9);
  EXPECT_LT(test::translation_error_mm(r.T_ref_scan, truth), 1e-9);
}

TEST(Horn, CollinearOrTooFewPointsAreNotWellPosed) {
  const std::vector<Eigen::Vector3d> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};
  EXPECT_FALSE(horn_transform(line, line).well_posed);
  const std::vector<Eigen::Vector3d> two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_FALSE(horn_transform(two, two).well_posed);
  const std::vector<Eigen::Vector3d> triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(horn_transform(triangle, triangle).well_posed);
}

TEST(Horn, MismatchedInputThrows) {
  const std::vector<Eigen::Vector3d> three{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(horn_transform(three, {{0, 0, 0}}), Error);
  EXPECT_THROW(horn_transform(three, three, {1.0, 1.0}), Error);
  EXPECT_THROW(horn_transform(three, three, {1.0, -1.0, 1.0}), Error);
}

}  // namespace
}  // namespace conform
