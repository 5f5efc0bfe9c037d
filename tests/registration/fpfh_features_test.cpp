// conform's own FPFH pieces (registration/src/fpfh_features.h) against closed forms and brute force: the outlier
// rule, the Darboux-frame angles, the histograms of a plane and of a moved patch, the nearest-histogram search; and
// against PCL's FPFHEstimation, the implementation conform used before (its thresholds were tuned on it).

// PCL's templates make GCC 12 report -Warray-bounds false positives inside Eigen's SSE loads of 3-float vectors; the
// warning is located in the intrinsics header, so the pragma must cover its first inclusion.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <pcl/features/fpfh.h>
#include <pcl/search/kdtree.h>
#pragma GCC diagnostic pop

#include "fpfh_features.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "conform/core/random.h"

namespace conform::detail {
namespace {

using V = Eigen::Vector3f;

// The rule of statistical_inliers by brute force: mean distance to the k nearest others, kept within mean + s std.
std::vector<std::size_t> brute_force_inliers(const std::vector<V>& points, int k, double sigmas) {
  std::vector<double> mean(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::vector<double> d;
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j != i) d.push_back(std::sqrt(static_cast<double>((points[i] - points[j]).squaredNorm())));
    }
    std::sort(d.begin(), d.end());
    mean[i] = std::accumulate(d.begin(), d.begin() + k, 0.0) / k;
  }
  const double mu = std::accumulate(mean.begin(), mean.end(), 0.0) / static_cast<double>(mean.size());
  double ss = 0.0;
  for (const double m : mean) ss += (m - mu) * (m - mu);
  const double limit = mu + sigmas * std::sqrt(ss / static_cast<double>(mean.size() - 1));
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < mean.size(); ++i) {
    if (mean[i] <= limit) kept.push_back(i);
  }
  return kept;
}

// A jittered 1 mm grid on a plane with five stray points 20-60 mm off it: the strays go, the rule is brute force's.
TEST(FpfhFeatures, StatisticalInliersDropStrayPointsByTheRule) {
  Random random(11);
  std::vector<V> points;
  for (int x = 0; x < 30; ++x) {
    for (int y = 0; y < 30; ++y) {
      points.emplace_back(static_cast<float>(x + random.uniform(-0.2, 0.2)),
                          static_cast<float>(y + random.uniform(-0.2, 0.2)), 0.0f);
    }
  }
  const std::size_t surface = points.size();
  for (int s = 0; s < 5; ++s)
    points.emplace_back(5.0f * static_cast<float>(s), 10.0f, 20.0f + 10.0f * static_cast<float>(s));
  const std::vector<std::size_t> kept = statistical_inliers(points, 8, 2.0);
  EXPECT_EQ(kept, brute_force_inliers(points, 8, 2.0));
  for (const std::size_t i : kept) EXPECT_LT(i, surface) << "a stray point was kept";
  EXPECT_GT(kept.size(), surface * 9 / 10);
  // k <= 0 or no more points than k: everything.
  EXPECT_EQ(statistical_inliers(points, 0, 2.0).size(), points.size());
  EXPECT_EQ(statistical_inliers(std::vector<V>(points.begin(), points.begin() + 5), 8, 2.0).size(), 5u);
}

TEST(FpfhFeatures, PairAnglesOfKnownPairs) {
  Eigen::Vector3f a;
  const V up(0, 0, 1);
  // Two points of a plane: every angle zero.
  ASSERT_TRUE(pair_angles(V(0, 0, 0), up, V(1, 0, 0), up, a));
  EXPECT_NEAR(a.norm(), 0.0f, 1e-7f);
  // The second normal tilted by 0.3 rad towards the line: it is nearer the line's direction, so it is the source
  // u = (sin 0.3, 0, cos 0.3), the line reversed, v = (0, 1, 0), w = (-cos 0.3, 0, sin 0.3): theta = 0.3, alpha = 0,
  // phi = -sin(0.3).
  const float t = 0.3f;
  ASSERT_TRUE(pair_angles(V(0, 0, 0), up, V(2, 0, 0), V(std::sin(t), 0, std::cos(t)), a));
  EXPECT_NEAR(a[0], t, 1e-6f);
  EXPECT_NEAR(a[1], 0.0f, 1e-7f);
  EXPECT_NEAR(a[2], -std::sin(t), 1e-6f);
  // Turned about the line instead: alpha = v . n_t = -sin(0.3).
  ASSERT_TRUE(pair_angles(V(0, 0, 0), up, V(2, 0, 0), V(0, std::sin(t), std::cos(t)), a));
  EXPECT_NEAR(a[1], -std::sin(t), 1e-6f);
  // The line 0.2 rad above the tangent plane of two parallel normals: phi = cos(angle to the normal) = sin(0.2).
  ASSERT_TRUE(pair_angles(V(0, 0, 0), up, V(std::cos(0.2f), 0, std::sin(0.2f)), up, a));
  EXPECT_NEAR(a[2], std::sin(0.2f), 1e-6f);
  // A target normal nearer the line than the source's: the ends swap, phi = -(the target's cosine) = -cos(0.2).
  ASSERT_TRUE(pair_angles(V(0, 0, 0), up, V(std::cos(0.2f), 0, std::sin(0.2f)), V(1, 0, 0), a));
  EXPECT_NEAR(a[2], -std::cos(0.2f), 1e-6f);
  // Coincident points, or a line along the source normal: no angles.
  EXPECT_FALSE(pair_angles(V(1, 1, 1), up, V(1, 1, 1), up, a));
  EXPECT_FALSE(pair_angles(V(0, 0, 0), up, V(0, 0, 1), up, a));
  // The same angles whichever end asks.
  Random random(5);
  for (int i = 0; i < 200; ++i) {
    const V p1 = V::Random(), p2 = V::Random();
    const V n1 = V::Random().normalized(), n2 = V::Random().normalized();
    Eigen::Vector3f forward, backward;
    const bool ok = pair_angles(p1, n1, p2, n2, forward);
    ASSERT_EQ(ok, pair_angles(p2, n2, p1, n1, backward));
    if (ok && std::abs(std::abs(n1.dot((p2 - p1).normalized())) - std::abs(n2.dot((p2 - p1).normalized()))) > 1e-3f) {
      EXPECT_NEAR((forward - backward).norm(), 0.0f, 1e-4f) << i;
    }
  }
}

// Every pair of a plane has all three angles at zero: the middle bin of each histogram holds all 100.
TEST(FpfhFeatures, APlaneFillsTheMiddleBins) {
  std::vector<V> points, normals;
  for (int x = 0; x < 12; ++x) {
    for (int y = 0; y < 12; ++y) {
      points.emplace_back(static_cast<float>(x), static_cast<float>(y), 0.0f);
      normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  }
  normals[0] = V::Constant(std::numeric_limits<float>::quiet_NaN());
  const std::vector<FpfhHistogram> h = fpfh_histograms(points, normals, 2.5f);
  ASSERT_EQ(h.size(), points.size());
  EXPECT_TRUE(std::isnan(h[0][0]));  // no normal: never matched
  for (std::size_t i = 1; i < h.size(); ++i) {
    for (int b = 0; b < 3 * kFpfhBins; ++b) {
      EXPECT_NEAR(h[i][static_cast<std::size_t>(b)], b % kFpfhBins == kFpfhBins / 2 ? 100.0f : 0.0f, 1e-3f)
          << "point " << i << " bin " << b;
    }
  }
}

// Random points of a curved patch (a saddle and a bump) with their exact normals.
void curved_patch(std::uint64_t seed, int count, std::vector<V>& points, std::vector<V>& normals) {
  Random random(seed);
  for (int i = 0; i < count; ++i) {
    const double x = random.uniform(-10.0, 10.0), y = random.uniform(-10.0, 10.0);
    const double z = 0.02 * (x * x - y * y) + 2.0 * std::exp(-(x * x + y * y) / 8.0);
    const double dzdx = 0.04 * x - 0.5 * x * std::exp(-(x * x + y * y) / 8.0);
    const double dzdy = -0.04 * y - 0.5 * y * std::exp(-(x * x + y * y) / 8.0);
    points.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
    normals.push_back(Eigen::Vector3d(-dzdx, -dzdy, 1.0).normalized().cast<float>());
  }
}

// The curved patch moved rigidly: the same histograms (the features describe shape, not place), each of the three
// summing to 100.
TEST(FpfhFeatures, HistogramsDoNotChangeWithARigidMotion) {
  std::vector<V> points, normals;
  curved_patch(3, 1500, points, normals);
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = Eigen::AngleAxisf(1.1f, V(0.3f, -0.5f, 0.8f).normalized()).toRotationMatrix();
  T.translation() = V(40.0f, -25.0f, 12.0f);
  std::vector<V> moved_points, moved_normals;
  for (std::size_t i = 0; i < points.size(); ++i) {
    moved_points.push_back(T * points[i]);
    moved_normals.push_back(T.linear() * normals[i]);
  }
  const std::vector<FpfhHistogram> a = fpfh_histograms(points, normals, 3.0f);
  const std::vector<FpfhHistogram> b = fpfh_histograms(moved_points, moved_normals, 3.0f);
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (int part = 0; part < 3; ++part) {
      float sum = 0.0f;
      for (int k = 0; k < kFpfhBins; ++k) sum += a[i][static_cast<std::size_t>(part * kFpfhBins + k)];
      EXPECT_NEAR(sum, 100.0f, 1e-3f);
    }
    for (std::size_t k = 0; k < a[i].size(); ++k)
      largest = std::max(largest, static_cast<double>(std::abs(a[i][k] - b[i][k])));
  }
  // A neighbour at the radius or a pair angle at a bin's edge may fall the other way in float: a few percent of
  // one neighbour's share at most.
  EXPECT_LT(largest, 2.0);
}

// The same points and normals through PCL's FPFHEstimation: the same histograms (here to the last bit; a pair's
// angle at a bin's edge could fall the other way if the float operations differed).
TEST(FpfhFeatures, HistogramsAreThoseOfPclsFpfhEstimation) {
  std::vector<V> points, normals;
  curved_patch(4, 1500, points, normals);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  pcl::PointCloud<pcl::Normal>::Ptr cloud_normals(new pcl::PointCloud<pcl::Normal>);
  for (std::size_t i = 0; i < points.size(); ++i) {
    cloud->push_back(pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z()));
    cloud_normals->push_back(pcl::Normal(normals[i].x(), normals[i].y(), normals[i].z()));
  }
  pcl::FPFHEstimation<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> fpfh;
  fpfh.setInputCloud(cloud);
  fpfh.setInputNormals(cloud_normals);
  fpfh.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  fpfh.setRadiusSearch(3.0);
  pcl::PointCloud<pcl::FPFHSignature33> expected;
  fpfh.compute(expected);
  const std::vector<FpfhHistogram> got = fpfh_histograms(points, normals, 3.0f);
  ASSERT_EQ(expected.size(), got.size());
  double sum = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    for (std::size_t k = 0; k < got[i].size(); ++k) {
      const double d = std::abs(static_cast<double>(got[i][k]) - static_cast<double>(expected[i].histogram[k]));
      sum += d;
      largest = std::max(largest, d);
    }
  }
  const double mean = sum / static_cast<double>(got.size() * got[0].size());
  std::printf("  FPFH against PCL's: mean |difference| %.2e, largest %.3f (of 100 a histogram)\n", mean, largest);
  EXPECT_LT(mean, 1e-4);
  EXPECT_LT(largest, 0.01);
}

TEST(FpfhFeatures, NearestHistogramsEqualBruteForce) {
  Random random(9);
  std::vector<FpfhHistogram> set(400);
  for (FpfhHistogram& h : set) {
    for (float& v : h) v = static_cast<float>(random.uniform(0.0, 100.0));
  }
  set[7].fill(std::numeric_limits<float>::quiet_NaN());
  const HistogramIndex index(set);
  std::vector<std::size_t> found;
  std::vector<float> d2;
  for (int q = 0; q < 50; ++q) {
    FpfhHistogram query;
    for (float& v : query) v = static_cast<float>(random.uniform(0.0, 100.0));
    std::vector<std::pair<double, std::size_t>> all;
    for (std::size_t i = 0; i < set.size(); ++i) {
      if (i == 7) continue;
      double s = 0.0;
      for (std::size_t k = 0; k < query.size(); ++k) s += (query[k] - set[i][k]) * (query[k] - set[i][k]);
      all.emplace_back(s, i);
    }
    std::sort(all.begin(), all.end());
    index.knn(query, 2, found, d2);
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0], all[0].second);
    EXPECT_EQ(found[1], all[1].second);
    EXPECT_NEAR(d2[0], all[0].first, 1e-3 * all[0].first);
  }
  // The NaN row is never found.
  index.knn(set[0], 400, found, d2);
  EXPECT_EQ(found.size(), 399u);
  EXPECT_EQ(std::count(found.begin(), found.end(), std::size_t{7}), 0);
  // A set of NaN rows only (every normal of a side undefined): nothing to find.
  const std::vector<FpfhHistogram> none(3, set[7]);
  const HistogramIndex empty(none);
  empty.knn(set[0], 2, found, d2);
  EXPECT_TRUE(found.empty());
  EXPECT_TRUE(d2.empty());
}

}  // namespace
}  // namespace conform::detail
