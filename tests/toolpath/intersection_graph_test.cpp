// Welding by name and the conditions (1a)-(1f) on hand-made segment soups: each failure names its condition.

#include "conform/toolpath/intersection_graph.h"

#include <cmath>

#include <gtest/gtest.h>

namespace conform {
namespace {

constexpr double kPi = 3.141592653589793;

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

TEST(IntersectionGraph, EmptyIsConditionA) {
  const CurveCheck check = check_intersection_graph(weld_segments({}));
  EXPECT_EQ(check.condition, "1a");
  EXPECT_NE(check.message.find("do not intersect"), std::string::npos) << check.message;
}

TEST(IntersectionGraph, DuplicateEdgeIsConditionC) {
  auto segments = ring(8);
  segments.push_back(segments[3]);
  EXPECT_EQ(check_intersection_graph(weld_segments(segments)).condition, "1c");
}

TEST(IntersectionGraph, OpenCurveIsConditionDAndNamesWhere) {
  auto segments = ring(8);
  segments.erase(segments.begin() + 2);  // the ends at azimuth 90 and 135 deg
  const CurveCheck check = check_intersection_graph(weld_segments(segments));
  EXPECT_EQ(check.condition, "1d");
  EXPECT_NE(check.message.find("azimuth"), std::string::npos) << check.message;
  const double deg = check.azimuth_rad * 180.0 / kPi;
  EXPECT_TRUE(std::abs(deg - 90.0) < 1e-9 || std::abs(deg - 135.0) < 1e-9) << deg;
}

TEST(IntersectionGraph, BranchIsConditionE) {
  auto segments = ring(8);
  IntersectionSegment spur;
  spur.ends[0] = crossing(0, 8);
  spur.ends[1] = crossing(4, 8);
  segments.push_back(spur);
  const CurveCheck check = check_intersection_graph(weld_segments(segments));
  EXPECT_EQ(check.condition, "1e");
  EXPECT_NE(check.message.find("3 edges meet"), std::string::npos) << check.message;
}

TEST(IntersectionGraph, TwoCurvesAreConditionFAndTheSecondIsLocated) {
  auto segments = ring(8, 0);
  const auto second = ring(6, 1);
  segments.insert(segments.end(), second.begin(), second.end());
  const CurveCheck check = check_intersection_graph(weld_segments(segments));
  EXPECT_EQ(check.condition, "1f");
  EXPECT_NE(check.message.find("2 separate"), std::string::npos) << check.message;
  EXPECT_EQ(check.where.z(), 5.0);  // a point of the second ring
}

TEST(IntersectionGraph, DegenerateEdgeIsConditionB) {
  auto segments = ring(8);
  segments[0].ends[1] = segments[0].ends[0];
  EXPECT_EQ(check_intersection_graph(weld_segments(segments)).condition, "1b");
}

}  // namespace
}  // namespace conform
