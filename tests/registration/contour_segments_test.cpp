// Contour subdivision (Béarée et al. 2010, Eqs. 5-6): osculating radii against circles of known radius, corners of a
// square found where they are, segments that tile the contour, no longer than epsilon, with the asked overlap.

#include "conform/registration/contour_segments.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

Polyline circle(double radius, int n) {
  Polyline c;
  c.closed = true;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    c.points.emplace_back(radius * std::cos(a), radius * std::sin(a), 0.0);
  }
  return c;
}

// A square of side `side` sampled every `step`, corners at (0,0), (side,0), (side,side), (0,side).
Polyline square(double side, double step) {
  Polyline c;
  c.closed = true;
  const Eigen::Vector3d corners[4] = {{0, 0, 0}, {side, 0, 0}, {side, side, 0}, {0, side, 0}};
  const int n = static_cast<int>(std::lround(side / step));
  for (int k = 0; k < 4; ++k) {
    for (int i = 0; i < n; ++i) c.points.push_back(corners[k] + (corners[(k + 1) % 4] - corners[k]) * i / n);
  }
  return c;
}

TEST(ContourSegments, OsculatingRadiusOfACircleIsItsRadius) {
  // Three points on a circle define it exactly; the points a window away are interpolated on a chord, inside the
  // circle by h^2 / 8R for a spacing h, against the triangle's sagitta w^2 / 2R: a relative error up to
  // h^2 / (4 w^2), 0.25% with h = w / 10. Tolerance 0.5%.
  const double window = 2.0;
  for (double r : {20.0, 150.0, 1000.0}) {
    const int n = static_cast<int>(std::ceil(2.0 * M_PI * r / (0.1 * window)));
    const std::vector<double> radii = osculating_radii(circle(r, n), window);
    for (double x : radii) EXPECT_NEAR(x, r, 5e-3 * r);
  }
}

TEST(ContourSegments, StraightLineHasInfiniteRadiusAndFindsNoCorner) {
  Polyline line;
  for (int i = 0; i <= 100; ++i) line.points.emplace_back(i, 2.0 * i, 0.0);
  for (double r : osculating_radii(line, 3.0)) EXPECT_TRUE(std::isinf(r));
  const ContourSegmentation s = segment_contour(line, {});
  EXPECT_TRUE(s.corners.empty());
  EXPECT_FALSE(s.closed);
  EXPECT_EQ(s.segments.front().overlap_before_mm, 0.0);  // an open contour's ends have no neighbour
  EXPECT_EQ(s.segments.back().overlap_after_mm, 0.0);
}

TEST(ContourSegments, SquareCornersAreSubdivisionPoints) {
  const Polyline sq = square(100.0, 0.25);
  ContourSegmentationOptions o;
  o.segment_length_mm = 30.0;
  const ContourSegmentation s = segment_contour(sq, o);
  ASSERT_EQ(s.corners.size(), 4u);
  for (int k = 0; k < 4; ++k) {  // exactly at the corner samples: the radius is smallest there
    EXPECT_EQ(s.corners[static_cast<std::size_t>(k)], k * 400);
  }
  // Each 100 mm side is cut into ceil(100 / 30) = 4 segments of 25 mm.
  ASSERT_EQ(s.segments.size(), 16u);
  double total = 0.0;
  for (const ContourSegment& g : s.segments) {
    EXPECT_NEAR(g.length_mm, 25.0, 1e-9);
    EXPECT_NEAR(g.overlap_before_mm, 0.5 * 0.3 * 25.0, 1e-9);
    total += g.length_mm;
  }
  EXPECT_NEAR(total, 400.0, 1e-9);
  EXPECT_TRUE(s.segments[0].starts_at_corner);
  EXPECT_TRUE(s.segments[3].ends_at_corner);
  EXPECT_FALSE(s.segments[1].starts_at_corner);
}

TEST(ContourSegments, SegmentsTileAClosedContourAndReachTheirOverlaps) {
  const Polyline c = circle(100.0, 2000);  // radius 100 > 15: no corner
  ContourSegmentationOptions o;
  o.segment_length_mm = 50.0;
  o.overlap = 0.4;
  const ContourSegmentation s = segment_contour(c, o);
  EXPECT_TRUE(s.corners.empty());
  const std::size_t n = s.segments.size();
  EXPECT_EQ(n, static_cast<std::size_t>(std::ceil(s.length_mm / 50.0)));
  for (std::size_t k = 0; k < n; ++k) {
    const ContourSegment& g = s.segments[k];
    const ContourSegment& next = s.segments[(k + 1) % n];
    EXPECT_NEAR(s.ahead(g.start_mm, next.start_mm), g.length_mm, 1e-9);  // no gap, no overlap of cores
    const double junction = next.start_mm;
    EXPECT_TRUE(s.reaches(k, junction + 0.99 * g.overlap_after_mm));
    EXPECT_FALSE(s.reaches(k, junction + 1.01 * g.overlap_after_mm));
    EXPECT_TRUE(s.reaches((k + 1) % n, junction - 0.99 * next.overlap_before_mm));
    EXPECT_NEAR(g.overlap_after_mm, 0.5 * 0.4 * std::min(g.length_mm, next.length_mm), 1e-9);
  }
}

TEST(ContourSegments, BadInputThrows) {
  ContourSegmentationOptions o;
  o.overlap = 1.0;
  EXPECT_THROW(segment_contour(circle(10, 100), o), Error);
  o = {};
  o.segment_length_mm = 0.0;
  EXPECT_THROW(segment_contour(circle(10, 100), o), Error);
  Polyline two;
  two.points = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(segment_contour(two, {}), Error);
  Polyline same;
  same.points.assign(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(segment_contour(same, {}), Error);
}

}  // namespace
}  // namespace conform
