// Algorithm 1 (ordering by azimuth), Eq. (2) resampling, arc-length resampling and smoothing, on curves whose
// answer is known in closed form; and the conditions (1h), [axis], [azimuth], [jordan].

#include "conform/toolpath/intersection/azimuth_path.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "conform/core/constants.h"

namespace conform {
namespace {

// A closed polygon through the given points, welded in a shuffled vertex order (so the ordering has work to do).
IntersectionGraph polygon(const std::vector<Eigen::Vector3d>& points, unsigned seed = 1) {
  const int n = static_cast<int>(points.size());
  std::vector<int> label(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) label[static_cast<std::size_t>(i)] = i;
  std::shuffle(label.begin(), label.end(), std::mt19937(seed));
  std::vector<IntersectionSegment> segments;
  for (int i = 0; i < n; ++i) {
    IntersectionSegment s;
    for (int k = 0; k < 2; ++k) {
      const int j = (i + k) % n;
      s.ends[k].v0 = label[static_cast<std::size_t>(j)];
      s.ends[k].v1 = s.ends[k].v0 + 1;
      s.ends[k].point = points[static_cast<std::size_t>(j)];
    }
    segments.push_back(s);
  }
  return weld_segments(segments);
}

// A saddle-like curve: radius r, height z = 10 cos 2 phi, sampled at uneven azimuths starting at 17 deg.
std::vector<Eigen::Vector3d> saddle(int n, double r = 100.0) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double phi = 0.3 + 2.0 * kPi * (i + 0.3 * std::sin(i)) / n;
    points.emplace_back(r * std::cos(phi), r * std::sin(phi), 10.0 * std::cos(2 * phi));
  }
  return points;
}

TEST(AzimuthPath, OrdersByIncreasingAzimuthFromTheSmallestEitherWayRound) {
  auto points = saddle(90);
  for (const bool reversed : {false, true}) {
    if (reversed) std::reverse(points.begin(), points.end());
    const AzimuthOrder order = order_by_azimuth(polygon(points));
    ASSERT_TRUE(order.check.ok) << order.check.message;
    ASSERT_EQ(order.points.size(), 90u);
    EXPECT_GE(order.azimuth_rad.front(), 0.0);
    for (std::size_t i = 1; i < order.points.size(); ++i) EXPECT_GT(order.azimuth_rad[i], order.azimuth_rad[i - 1]);
    EXPECT_LT(order.azimuth_rad.back() - order.azimuth_rad.front(), 2.0 * kPi);
  }
}

TEST(AzimuthPath, Eq2ResamplesByLinearInterpolationAtEqualAzimuths) {
  // A polygon with vertices at 0, 90, 180, 270 deg: the resampled points lie on its straight sides.
  const std::vector<Eigen::Vector3d> square = {{10, 0, 0}, {0, 10, 4}, {-10, 0, 0}, {0, -10, 4}};
  PathSamplingOptions options;
  options.step_rad = kPi / 4;
  const SampledPath path = sample_path(order_by_azimuth(polygon(square)), options);
  ASSERT_EQ(path.points.size(), 8u);
  EXPECT_NEAR(path.phi_rad[1], kPi / 4, 1e-15);
  // At 45 deg the ray meets the side from (10, 0, 0) to (0, 10, 4) at its middle.
  EXPECT_NEAR((path.points[1] - Eigen::Vector3d(5, 5, 2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((path.points[0] - Eigen::Vector3d(10, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(path.length_mm, 8.0 * std::sqrt(50.0 + 4.0), 1e-9);
}

TEST(AzimuthPath, ArcLengthStepsAreEqualWhereAzimuthStepsAreNot) {
  // An off-centre circle: equal azimuths bunch on the near side; equal arc lengths do not.
  std::vector<Eigen::Vector3d> circle;
  for (int i = 0; i < 2000; ++i) {
    const double t = 2.0 * kPi * i / 2000;
    circle.emplace_back(60.0 + 100.0 * std::cos(t), 100.0 * std::sin(t), 0.0);
  }
  const AzimuthOrder order = order_by_azimuth(polygon(circle));
  ASSERT_TRUE(order.check.ok) << order.check.message;
  PathSamplingOptions by_angle;
  by_angle.step_rad = 2.0 * kPi / 100;
  const SampledPath a = sample_path(order, by_angle);
  EXPECT_GT(a.max_step_mm / a.min_step_mm, 3.0);
  PathSamplingOptions by_length;
  by_length.spacing = PathSpacing::kArcLength;
  by_length.step_mm = 2.0 * kPi * 100.0 / 100;
  const SampledPath b = sample_path(order, by_length);
  EXPECT_EQ(b.points.size(), 100u);
  // Equal arcs of the 2000-gon, measured as chords: equal to the chord's own sagitta error (~1e-4 relative).
  EXPECT_LT(b.max_step_mm / b.min_step_mm, 1.001);
  EXPECT_NEAR(b.phi_rad[0], 0.0, 0.0);
}

TEST(AzimuthPath, SmoothingPullsANoisyCurveTowardsTheTruth) {
  auto points = saddle(400);
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.3);
  auto noisy = points;
  for (Eigen::Vector3d& p : noisy) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const AzimuthOrder order = order_by_azimuth(polygon(noisy), 2.0);
  ASSERT_TRUE(order.check.ok) << order.check.message;
  PathSamplingOptions options;
  options.step_rad = kPi / 90;
  const auto error = [&](const SampledPath& path) {
    double worst = 0.0;
    for (std::size_t i = 0; i < path.points.size(); ++i) {
      const double phi = std::atan2(path.points[i].y(), path.points[i].x());
      worst = std::max(worst, std::abs(path.points[i].z() - 10.0 * std::cos(2 * phi)));
    }
    return worst;
  };
  const double raw = error(sample_path(order, options));
  options.smoothing_rms_mm = 0.3 * std::sqrt(3.0);
  const SampledPath smooth = sample_path(order, options);
  ASSERT_TRUE(smooth.smoothed);
  // 400 noisy points against a spline of ~200 control points: the worst error drops by a third or more.
  EXPECT_LT(error(smooth), 0.7 * raw) << raw;
}

TEST(AzimuthPath, BacktrackingBeyondTheToleranceIsAzimuth) {
  auto points = saddle(36);
  points[10] = points[8];  // a step back of two samples (~35 mm on r = 100)
  points[10].z() += 1.0;
  const AzimuthOrder strict = order_by_azimuth(polygon(points), 0.05);
  EXPECT_EQ(strict.check.condition, "azimuth");
  EXPECT_NE(strict.check.message.find("not parameterisable by azimuth"), std::string::npos);
  const AzimuthOrder lenient = order_by_azimuth(polygon(points), 50.0);
  EXPECT_TRUE(lenient.check.ok);
  EXPECT_GE(lenient.dropped, 1u);
}

TEST(AzimuthPath, ALoopBesideTheAxisIsJordan) {
  std::vector<Eigen::Vector3d> loop;
  for (int i = 0; i < 40; ++i) {
    const double t = 2.0 * kPi * i / 40;
    loop.emplace_back(100.0 + 20.0 * std::cos(t), 20.0 * std::sin(t), 0.0);
  }
  const AzimuthOrder order = order_by_azimuth(polygon(loop), 0.0);
  EXPECT_FALSE(order.check.ok);
  EXPECT_EQ(order.check.condition, "jordan") << order.check.message;
}

TEST(AzimuthPath, AVertexOnTheAxisIsAxis) {
  auto points = saddle(12);
  points[3] = Eigen::Vector3d(0.0, 0.0, 5.0);
  EXPECT_EQ(order_by_azimuth(polygon(points)).check.condition, "axis");
}

// (1h): coincident neighbours (a zero-length edge) are merged; a curve that comes back to one of its own vertices
// elsewhere fails.
TEST(AzimuthPath, CoincidentVerticesAreMergedAlongTheCurveAndFailElsewhere) {
  auto points = saddle(24);
  points.insert(points.begin() + 5, points[5]);
  const AzimuthOrder merged = order_by_azimuth(polygon(points));
  ASSERT_TRUE(merged.check.ok) << merged.check.message;
  EXPECT_EQ(merged.merged, 1u);
  EXPECT_EQ(merged.points.size(), 24u);
  auto touching = saddle(24);
  touching[12] = touching[3];
  EXPECT_EQ(order_by_azimuth(polygon(touching), 1e3).check.condition, "1h");
}

// Noise on a shallow crossing makes the walk step back locally: within the tolerance it is dropped, and smoothing
// the cycle first (before the azimuth test) removes the backtracks altogether.
TEST(AzimuthPath, SmoothingBeforeTheAzimuthTestRemovesNoiseBacktracks) {
  auto points = saddle(2000);  // 0.31 mm apart on r = 100
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (Eigen::Vector3d& p : points) p += Eigen::Vector3d(noise(rng), noise(rng), 0.0);
  AzimuthOrderOptions options;
  options.backtrack_tolerance_mm = 0.05;
  EXPECT_EQ(order_by_azimuth(polygon(points), options).check.condition, "azimuth");
  options.smoothing_mm2 = 2000 * 2 * 0.3 * 0.3;
  const AzimuthOrder smoothed = order_by_azimuth(polygon(points), options);
  ASSERT_TRUE(smoothed.check.ok) << smoothed.check.message;
  EXPECT_TRUE(smoothed.smoothed);
  EXPECT_EQ(smoothed.dropped, 0u);
  EXPECT_NEAR(smoothed.smoothing_rms_mm, 0.3 * std::sqrt(2.0), 0.05);
}

TEST(AzimuthPath, InvalidStepsAreRejected) {
  const AzimuthOrder order = order_by_azimuth(polygon(saddle(12)));
  PathSamplingOptions options;
  options.step_rad = 0.0;
  EXPECT_FALSE(options.IsValid(nullptr));
  EXPECT_ANY_THROW(sample_path(order, options));
  options = {};
  options.spacing = PathSpacing::kArcLength;
  options.step_mm = -1.0;
  EXPECT_ANY_THROW(sample_path(order, options));
}

}  // namespace
}  // namespace conform
