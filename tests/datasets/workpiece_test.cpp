// The machined workpiece generator (datasets/workpiece.h): heights against the formula at the features, samples on
// the surface within the window with the stated noise, outliers where asked, the same seed the same points, bad
// options refused.

#include "conform/datasets/workpiece.h"

#include <gtest/gtest.h>

#include <cmath>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(Workpiece, HeightFollowsTheFeatures) {
  const WorkpieceOptions o;  // 160 x 100 mm
  EXPECT_DOUBLE_EQ(workpiece_height(o, -70.0, -45.0), 0.0);   // top face
  EXPECT_DOUBLE_EQ(workpiece_height(o, 0.0, 40.0), -6.0);     // on the shoulder (y >= 25)
  EXPECT_NEAR(workpiece_height(o, 0.0, 24.6), -3.0, 1e-12);   // half-way down its wall (smoothstep(1/2))
  EXPECT_DOUBLE_EQ(workpiece_height(o, -40.0, -5.0), -8.0);   // in the rectangular pocket
  EXPECT_DOUBLE_EQ(workpiece_height(o, 44.8, -25.0), -10.0);  // in the bore
  EXPECT_DOUBLE_EQ(workpiece_height(o, 35.2, 12.0), -4.0);    // in the slot
  EXPECT_DOUBLE_EQ(workpiece_height(o, 75.0, 12.0), 0.0);     // beyond the slot's end
}

TEST(Workpiece, SamplesLieOnTheSurfaceInTheWindow) {
  WorkpieceOptions o;
  o.x_from = 0.2;
  o.x_to = 0.7;
  o.noise_mm = 0.2;
  const std::vector<Eigen::Vector3d> a = workpiece_samples(o);
  ASSERT_EQ(a.size(), o.points);
  double sum = 0.0, sq = 0.0;
  for (const Eigen::Vector3d& p : a) {
    EXPECT_GE(p.x(), -48.0);
    EXPECT_LE(p.x(), 32.0);
    EXPECT_LE(std::abs(p.y()), 50.0);
    const double r = p.z() - workpiece_height(o, p.x(), p.y());
    sum += r;
    sq += r * r;
  }
  const double n = static_cast<double>(a.size());
  EXPECT_NEAR(sum / n, 0.0, 0.006);
  EXPECT_NEAR(std::sqrt(sq / n), 0.2, 0.006);
  EXPECT_EQ(workpiece_samples(o), a);
  o.seed = 2;
  EXPECT_NE(workpiece_samples(o), a);
}

TEST(Workpiece, OutliersTakeTheirShare) {
  WorkpieceOptions o;
  o.noise_mm = 0.0;
  o.outlier_share = 0.1;
  std::size_t off = 0;
  for (const Eigen::Vector3d& p : workpiece_samples(o)) off += std::abs(p.z() - workpiece_height(o, p.x(), p.y())) > 1e-9;
  EXPECT_NEAR(static_cast<double>(off) / static_cast<double>(o.points), 0.1, 0.01);
}

TEST(Workpiece, BadOptionsAreRefused) {
  WorkpieceOptions o;
  o.x_from = 0.6;
  o.x_to = 0.5;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("window"), std::string::npos);
  EXPECT_THROW(workpiece_samples(o), Error);
  o = WorkpieceOptions();
  o.noise_mm = -1.0;
  EXPECT_FALSE(o.IsValid(nullptr));
  o = WorkpieceOptions();
  o.outlier_share = 1.0;
  EXPECT_FALSE(o.IsValid(nullptr));
}

}  // namespace
}  // namespace conform
