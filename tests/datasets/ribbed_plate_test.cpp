// The ribbed plate generator (datasets/ribbed_plate.h): heights and normals against the formula, samples on the
// surface with the stated noise, the same seed the same points, bad options refused.

#include "conform/datasets/ribbed_plate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(RibbedPlate, HeightAndNormalFollowTheFormula) {
  const RibbedPlateOptions o;  // four ribs at x = -60, -20, 20, 60; 6 mm wide, 8 mm high, y in [-50, 50]
  EXPECT_DOUBLE_EQ(ribbed_plate_height(o, 20.0, 0.0), 8.0);     // on a rib
  EXPECT_DOUBLE_EQ(ribbed_plate_height(o, 0.0, 0.0), 0.0);      // between ribs
  EXPECT_DOUBLE_EQ(ribbed_plate_height(o, 20.0, 70.0), 0.0);    // beyond the rib's end
  EXPECT_DOUBLE_EQ(ribbed_plate_height(o, 23.5, 0.0), 4.0);     // half-way down the wall (smoothstep(1/2) = 1/2)
  EXPECT_DOUBLE_EQ(ribbed_plate_height(o, -60.0, -50.5), 4.0);  // half-way down the end
  for (const auto& [x, y] : {std::pair{23.3, 10.0}, std::pair{-59.0, 50.4}, std::pair{5.0, 5.0}}) {
    const double h = 1e-6;
    const double gx = (ribbed_plate_height(o, x + h, y) - ribbed_plate_height(o, x - h, y)) / (2 * h);
    const double gy = (ribbed_plate_height(o, x, y + h) - ribbed_plate_height(o, x, y - h)) / (2 * h);
    const Eigen::Vector3d expected = Eigen::Vector3d(-gx, -gy, 1.0).normalized();
    EXPECT_LT((ribbed_plate_normal(o, x, y) - expected).norm(), 1e-6) << x << " " << y;
  }
}

TEST(RibbedPlate, SamplesLieOnTheSurfaceWithTheNoise) {
  RibbedPlateOptions o;
  o.points = 20000;
  o.noise_mm = 0.05;
  const std::vector<Eigen::Vector3d> a = ribbed_plate_samples(o);
  ASSERT_EQ(a.size(), 20000u);
  double sum = 0.0, sq = 0.0;
  for (const Eigen::Vector3d& p : a) {
    EXPECT_LE(std::abs(p.x()), 100.0);
    EXPECT_LE(std::abs(p.y()), 75.0);
    const double r = p.z() - ribbed_plate_height(o, p.x(), p.y());
    sum += r;
    sq += r * r;
  }
  const double n = static_cast<double>(a.size());
  EXPECT_NEAR(sum / n, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sq / n), 0.05, 0.002);
  EXPECT_EQ(ribbed_plate_samples(o), a);
  o.seed = 2;
  EXPECT_NE(ribbed_plate_samples(o), a);
  o.ribs = 6;  // 5 x 40 + 6 + 2 > 200 mm
  EXPECT_THROW(ribbed_plate_samples(o), Error);
  o = RibbedPlateOptions{};
  o.noise_mm = -1.0;
  EXPECT_THROW(ribbed_plate_samples(o), Error);
}

}  // namespace
}  // namespace conform
