// compute_deviation against an independent brute force: every point's distance to every triangle (projection onto
// the plane when it falls inside, else the nearest edge point), signed by a ray-casting inside test of the closed
// reference; and the statistics of both agree to 1e-9 mm.

#include "conform/evaluation/deviation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/evaluation/statistics.h"
#include "test_meshes.h"

namespace conform {
namespace {

using V = Eigen::Vector3d;

// A closed, non-convex "bumpy sphere": a latitude-longitude sphere whose radius varies with the direction.
Mesh bumpy_sphere(int rings, int segments) {
  return test::lat_long_sphere(
      rings, segments, [](double polar, double az) { return 10.0 + 2.0 * std::sin(3 * az) * std::sin(2 * polar); });
}

double segment_distance(const V& p, const V& u, const V& v) {
  const V d = v - u;
  const double t = d.squaredNorm() > 0.0 ? std::clamp((p - u).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (u + t * d)).norm();
}

double triangle_distance(const V& p, const V& a, const V& b, const V& c) {
  double best = std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
  const V n = (b - a).cross(c - a);
  const V q = p - (p - a).dot(n) / n.squaredNorm() * n;
  if ((b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0) {
    best = std::min(best, (p - q).norm());
  }
  return best;
}

// Inside when a ray from p crosses the surface an odd number of times (Moeller & Trumbore 1997 per triangle); the
// direction is skewed so that it does not run through edges of the regular test mesh.
bool inside(const Mesh& m, const V& p) {
  const V dir = V(0.8931, 0.3127, 0.3235).normalized();
  int crossings = 0;
  for (const Face& f : m.faces) {
    const V& a = m.vertices[f[0]];
    const V e1 = m.vertices[f[1]] - a, e2 = m.vertices[f[2]] - a;
    const V h = dir.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-15) continue;
    const V s = p - a;
    const double u = s.dot(h) / det;
    const V q = s.cross(e1);
    const double v = dir.dot(q) / det;
    const double t = e2.dot(q) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && t > 0) ++crossings;
  }
  return crossings % 2 == 1;
}

std::vector<double> brute_force(const std::vector<V>& scan, const Mesh& reference) {
  std::vector<double> d(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const Face& f : reference.faces) {
      best = std::min(best, triangle_distance(scan[i], reference.vertices[f[0]], reference.vertices[f[1]],
                                              reference.vertices[f[2]]));
    }
    d[i] = inside(reference, scan[i]) ? -best : best;
  }
  return d;
}

// Points in a shell around the surface: reference vertices and edge midpoints moved by up to +-1.5 mm.
std::vector<V> scan_near(const Mesh& reference, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::vector<V> scan;
  for (const Face& f : reference.faces) {
    const V mid = 0.5 * (reference.vertices[f[0]] + reference.vertices[f[1]]);
    scan.push_back(mid + V(u(rng), u(rng), u(rng)));
    scan.push_back(reference.vertices[f[2]] + V(u(rng), u(rng), u(rng)));
  }
  return scan;
}

void expect_same_statistics(const DeviationStatistics& a, const DeviationStatistics& b) {
  EXPECT_EQ(a.count, b.count);
  const double pairs[][2] = {{a.min_mm, b.min_mm},         {a.max_mm, b.max_mm},          {a.mean_mm, b.mean_mm},
                             {a.std_mm, b.std_mm},         {a.rms_mm, b.rms_mm},          {a.p5_mm, b.p5_mm},
                             {a.p50_mm, b.p50_mm},         {a.p95_mm, b.p95_mm},          {a.p99_mm, b.p99_mm},
                             {a.p95_abs_mm, b.p95_abs_mm}, {a.mean_abs_mm, b.mean_abs_mm}};
  for (const auto& p : pairs) EXPECT_NEAR(p[0], p[1], 1e-9);
  EXPECT_EQ(a.in_tolerance_pct, b.in_tolerance_pct);
  EXPECT_EQ(a.above_pct, b.above_pct);
  EXPECT_EQ(a.below_pct, b.below_pct);
}

TEST(Deviation, SignedDistancesAndStatisticsMatchBruteForceToANanometre) {
  const Mesh reference = bumpy_sphere(14, 20);
  const std::vector<V> scan = scan_near(reference, 42);
  DeviationOptions flat;  // the triangles as they are, what the brute force measures
  flat.smooth_surface = false;
  const DeviationResult result = compute_deviation(scan, reference, flat);
  ASSERT_EQ(result.deviation_mm.size(), scan.size());
  EXPECT_TRUE(result.is_signed());
  EXPECT_EQ(result.matched, scan.size());
  EXPECT_EQ(result.unmatched, 0u);
  EXPECT_EQ(result.note, "");
  const std::vector<double> expected = brute_force(scan, reference);
  int inside_points = 0;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    ASSERT_NEAR(result.deviation_mm[i], expected[i], 1e-9) << "point " << i << " " << scan[i].transpose();
    ASSERT_NEAR((scan[i] - result.closest[i]).norm(), std::abs(expected[i]), 1e-9);
    inside_points += expected[i] < 0.0;
  }
  EXPECT_GT(inside_points, static_cast<int>(scan.size()) / 4);  // both sides are exercised
  DeviationStatisticsOptions with_band;
  with_band.tolerance_mm = 0.5;
  expect_same_statistics(deviation_statistics(result.deviation_mm, with_band),
                         deviation_statistics(expected, with_band));
}

TEST(Deviation, ACloudReferenceGivesUnsignedDistancesToTheNearestPointWithANote) {
  Mesh reference = bumpy_sphere(10, 12);
  const std::vector<V> scan = scan_near(reference, 3);
  reference.faces.clear();
  const DeviationResult result = compute_deviation(scan, reference);
  EXPECT_FALSE(result.is_signed());
  EXPECT_NE(result.note.find("unsigned"), std::string::npos) << result.note;
  for (std::size_t i = 0; i < scan.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const V& q : reference.vertices) best = std::min(best, (scan[i] - q).norm());
    ASSERT_EQ(result.deviation_mm[i], best) << "point " << i;
  }
}

TEST(Deviation, PointsBeyondTheMaximumDistanceAreUnmatched) {
  Mesh square;  // z = 0, facing +z
  square.vertices = {V(0, 0, 0), V(10, 0, 0), V(10, 10, 0), V(0, 10, 0)};
  square.faces = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<V> scan = {V(5, 5, 2.5), V(50, 5, 0), V(4, 3, 0.5), V(6, 2, -2.0)};
  DeviationOptions options;
  options.max_distance_mm = 2.0;  // inclusive
  const DeviationResult result = compute_deviation(scan, square, options);
  EXPECT_TRUE(std::isnan(result.deviation_mm[0]));
  EXPECT_TRUE(std::isnan(result.deviation_mm[1]));
  EXPECT_TRUE(std::isnan(result.closest[1].x()));
  EXPECT_EQ(result.deviation_mm[2], 0.5);
  EXPECT_EQ(result.deviation_mm[3], -2.0);
  EXPECT_EQ(result.closest[3], V(6, 2, 0));
  EXPECT_EQ(result.matched, 2u);
  EXPECT_EQ(result.unmatched, 2u);
  const DeviationStatistics s = deviation_statistics(result.deviation_mm);
  EXPECT_EQ(s.count, 2u);
  EXPECT_EQ(s.excluded, 2u);
}

TEST(Deviation, IsDeterministicAndReportsProgress) {
  const Mesh reference = bumpy_sphere(12, 16);
  std::vector<V> scan;
  for (int k = 0; k < 60; ++k) {  // more than one chunk of work per thread
    for (const V& p : scan_near(reference, static_cast<std::uint64_t>(k))) scan.push_back(p);
  }
  std::vector<double> fractions;
  DeviationOptions options;
  options.progress = [&](std::string_view stage, double f) {
    EXPECT_EQ(stage, "deviation");
    fractions.push_back(f);
  };
  const DeviationResult a = compute_deviation(scan, reference, options);
  const DeviationResult b = compute_deviation(scan, reference);
  for (std::size_t i = 0; i < scan.size(); ++i) ASSERT_EQ(a.deviation_mm[i], b.deviation_mm[i]);
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
}

TEST(Deviation, BadInputIsAnErrorNamingWhatIsWrong) {
  const Mesh reference = bumpy_sphere(6, 8);
  const std::vector<V> with_nan = {V(0, 0, 0), V(0, std::nan(""), 0)};
  try {
    compute_deviation(with_nan, reference);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scan point 1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(compute_deviation({V(0, 0, 0)}, Mesh{}), Error);
  DeviationOptions bad;
  bad.max_distance_mm = 0.0;
  EXPECT_THROW(compute_deviation({V(0, 0, 0)}, reference, bad), Error);
  bad.max_distance_mm = std::nan("");
  EXPECT_THROW(compute_deviation({V(0, 0, 0)}, reference, bad), Error);
  EXPECT_EQ(compute_deviation({}, reference).deviation_mm.size(), 0u);
}

}  // namespace
}  // namespace conform
