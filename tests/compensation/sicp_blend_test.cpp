// Blending of segment transforms: the sinusoidal weight is exactly 0 and 1 at an overlap's ends with zero slope
// there (C1), and the blended image of a point moving along the contour has no jump at a junction.

#include "conform/compensation/sicp_blend.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

ContourSegmentation two_segment_line() {
  Polyline line;
  for (int i = 0; i <= 100; ++i) line.points.emplace_back(i, 0.0, 0.0);
  ContourSegmentationOptions o;
  o.segment_length_mm = 50.0;
  o.overlap = 0.4;  // 20 mm overlap centred on s = 50: [40, 60]
  return segment_contour(line, o);
}

TEST(SicpBlend, WeightIsExactlyZeroAndOneWithZeroSlopeAtTheEnds) {
  EXPECT_EQ(sinusoidal_weight(0.0), 0.0);
  EXPECT_EQ(sinusoidal_weight(1.0), 1.0);
  EXPECT_EQ(sinusoidal_weight(-0.5), 0.0);
  EXPECT_EQ(sinusoidal_weight(1.5), 1.0);
  EXPECT_DOUBLE_EQ(sinusoidal_weight(0.5), 0.5);
  const double h = 1e-6;  // slope pi/2 sin(pi u) is 0 at the ends: a one-sided difference of h gives O(h^2)
  EXPECT_LT(sinusoidal_weight(h) / h, 1e-5);
  EXPECT_LT((1.0 - sinusoidal_weight(1.0 - h)) / h, 1e-5);
}

TEST(SicpBlend, WeightsOverTheOverlap) {
  const ContourSegmentation g = two_segment_line();
  ASSERT_EQ(g.segments.size(), 2u);
  EXPECT_EQ(blend_at(g, 30.0).weight, 0.0);
  const BlendAt start = blend_at(g, 40.0);
  EXPECT_EQ(start.segment, 0u);
  EXPECT_NEAR(start.weight, 0.0, 1e-12);
  EXPECT_NEAR(blend_at(g, 50.0).weight, 0.5, 1e-12);
  const BlendAt end = blend_at(g, 60.0 - 1e-9);
  EXPECT_EQ(end.next, 1u);
  EXPECT_NEAR(end.weight, 1.0, 1e-12);
  const BlendAt after = blend_at(g, 70.0);
  EXPECT_EQ(after.segment, 1u);
  EXPECT_EQ(after.weight, 0.0);
}

TEST(SicpBlend, BlendedPathHasNoJumpAtAJunction) {
  const ContourSegmentation g = two_segment_line();
  std::vector<Eigen::Isometry3d> T(2, Eigen::Isometry3d::Identity());
  T[1].translation() = Eigen::Vector3d(0.0, 0.0, 1.0);  // the second segment 1 mm higher
  double largest_step = 0.0;
  Eigen::Vector3d last = blend_point(g, T, 0.0, Eigen::Vector3d::Zero());
  for (int i = 1; i <= 10000; ++i) {  // 0.01 mm steps
    const double s = 0.01 * i;
    const Eigen::Vector3d p = blend_point(g, T, s, Eigen::Vector3d(s, 0.0, 0.0));
    largest_step = std::max(largest_step, std::abs(p.z() - last.z()));
    last = p;
  }
  // The steepest slope of the 1 mm rise over 20 mm is pi/2 * 1/20 mm per mm: 0.00079 mm per 0.01 mm step.
  EXPECT_LT(largest_step, 0.0008);
  EXPECT_NEAR(blend_point(g, T, 55.0, Eigen::Vector3d(55, 0, 0)).z(), 0.5 * (1.0 - std::cos(M_PI * 0.75)), 1e-12);
  EXPECT_EQ(blend_normal(g, T, 20.0, Eigen::Vector3d::UnitZ()), Eigen::Vector3d::UnitZ());
}

TEST(SicpBlend, NoSegmentsThrows) {
  ContourSegmentation empty;
  EXPECT_THROW(blend_at(empty, 1.0), Error);
}

}  // namespace
}  // namespace conform
