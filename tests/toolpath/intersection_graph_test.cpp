// Welding by name, the paper's conditions (1a), (1d), (1i) and the project's [intersect], [one-curve] on hand-made segment soups: each failure names its condition.

#include "conform/toolpath/intersection/intersection_graph.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/constants.h"

namespace conform {
namespace {

// A crossing named by (mesh A edge (i, i + 1), triangle 0), at a point of a circle of radius 10 at azimuth i.
EdgeCrossing crossing(int i, int n, int curve = 0) {
  EdgeCrossing c;
  c.v0 = i + 1000 * curve;
  c.v1 = c.v0 + 1;
  c.triangle = curve;
  const double a = 2.0 * kPi * i / n;
  c.point = Eigen::Vector3d(10.0 * std::cos(a), 10.0 * std::sin(a), curve * 5.0);
  return c;
}

std::vector<IntersectionSegment> ring(int n, int curve = 0) {
  std::vector<IntersectionSegment> segments;
  for (int i = 0; i < n; ++i) {
    IntersectionSegment s;
    s.face_a = i;
    s.ends[0] = crossing(i, n, curve);
    s.ends[1] = crossing((i + 1) % n, n, curve);
    segments.push_back(s);
  }
  return segments;
}

TEST(IntersectionGraph, ARingWeldsIntoOneClosedCurve) {
  const IntersectionGraph graph = weld_segments(ring(12));
  EXPECT_EQ(graph.vertices.size(), 12u);
  EXPECT_EQ(graph.edges.size(), 12u);
  EXPECT_TRUE(check_intersection_graph(graph).ok);
  EXPECT_EQ(count_components(graph), 1);
}

TEST(IntersectionGraph, EmptyIsIntersect) {
  const CurveCheck check = check_intersection_graph(weld_segments({}));
  EXPECT_EQ(check.condition, "intersect");
  EXPECT_EQ(check.message.rfind("[intersect]", 0), 0u) << check.message;
  EXPECT_NE(check.message.find("do not intersect"), std::string::npos) << check.message;
}

TEST(IntersectionGraph, DuplicateEdgeIsConditionI) {
  auto segments = ring(8);
  segments.push_back(segments[3]);
  EXPECT_EQ(check_intersection_graph(weld_segments(segments)).condition, "1i");
}

TEST(IntersectionGraph, OpenCurveIsConditionAAndNamesWhere) {
  auto segments = ring(8);
  segments.erase(segments.begin() + 2);  // the ends at azimuth 90 and 135 deg
  const CurveCheck check = check_intersection_graph(weld_segments(segments));
  EXPECT_EQ(check.condition, "1a");
  EXPECT_EQ(check.message.rfind("(1a)", 0), 0u) << check.message;
  EXPECT_NE(check.message.find("azimuth"), std::string::npos) << check.message;
  const double deg = check.azimuth_rad * 180.0 / kPi;
  EXPECT_TRUE(std::abs(deg - 90.0) < 1e-9 || std::abs(deg - 135.0) < 1e-9) << deg;
}

TEST(IntersectionGraph, BranchIsConditionA) {
  auto segments = ring(8);
  IntersectionSegment spur;
  spur.ends[0] = crossing(0, 8);
  spur.ends[1] = crossing(4, 8);
  segments.push_back(spur);
  const CurveCheck check = check_intersection_graph(weld_segments(segments));
  EXPECT_EQ(check.condition, "1a");
  EXPECT_NE(check.message.find("3 edges meet"), std::string::npos) << check.message;
}

TEST(IntersectionGraph, TwoCurvesAreOneCurveFailureAndTheSecondIsLocated) {
  auto segments = ring(8, 0);
  const auto second = ring(6, 1);
  segments.insert(segments.end(), second.begin(), second.end());
  const CurveCheck check = check_intersection_graph(weld_segments(segments));
  EXPECT_EQ(check.condition, "one-curve");
  EXPECT_NE(check.message.find("2 separate"), std::string::npos) << check.message;
  EXPECT_EQ(check.where.z(), 5.0);  // a point of the second ring
}

TEST(IntersectionGraph, DegenerateEdgeIsConditionD) {
  auto segments = ring(8);
  segments[0].ends[1] = segments[0].ends[0];
  EXPECT_EQ(check_intersection_graph(weld_segments(segments)).condition, "1d");
}

// A small loop beside the main one (a noise island) is dropped and reported; one of similar size still fails.
TEST(IntersectionGraph, IslandsFarShorterThanTheCurveAreDroppedSimilarLoopsFail) {
  auto segments = ring(8, 0);
  const auto second = ring(6, 1);
  segments.insert(segments.end(), second.begin(), second.end());
  const IntersectionGraph graph = weld_segments(segments);
  // Perimeters 61.2 mm (8 sides on r = 10) and 60.0 mm (6 sides): a ratio of 0.98.
  const MainCurve strict = select_main_curve(graph, 0.5);
  EXPECT_EQ(strict.check.condition, "one-curve");
  const MainCurve lenient = select_main_curve(graph, 0.99);
  ASSERT_TRUE(lenient.check.ok) << lenient.check.message;
  EXPECT_EQ(lenient.islands, 1u);
  EXPECT_EQ(lenient.island_vertices, 6u);
  EXPECT_EQ(lenient.graph.vertices.size(), 8u);
  EXPECT_EQ(lenient.graph.edges.size(), 8u);
  EXPECT_GT(lenient.main_length_mm, lenient.longest_island_mm);
  EXPECT_TRUE(check_intersection_graph(lenient.graph).ok);
}

}  // namespace
}  // namespace conform
