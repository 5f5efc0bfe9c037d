// Scene: the origin is the mean position; thinning keeps every k-th point to the limit and says so; mesh thinning
// by vertex clustering stays under the triangle limit with a subset of the vertices; bad arrays are refused.

#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "conform/report/scene.h"

namespace conform::html {
namespace {

// A flat n x n grid of 1 mm squares, two triangles each.
Mesh grid_mesh(int n) {
  Mesh m;
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) m.vertices.emplace_back(x, y, 0.01 * x * y);
  }
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  }
  return m;
}

TEST(ReportScene, OriginIsTheMeanOfAllPositions) {
  Scene s;
  s.add_points("a", {{1, 2, 3}, {3, 2, 1}}, kBlue);
  s.add_polyline("b", {{10, 10, 10}, {10, 10, 10}}, kRed);
  EXPECT_LT((s.origin() - Eigen::Vector3d(6.0, 6.0, 6.0)).norm(), 1e-12);
}

TEST(ReportScene, PointsThinnedByStrideToTheirShare) {
  Scene::Limits limits;
  limits.max_points = 100;
  Scene s(limits);
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 1000; ++i) p.emplace_back(i, 0, 0);
  s.add_points("scan", p, kBlue);
  s.add_points("small", std::vector<Eigen::Vector3d>(p.begin(), p.begin() + 250), kRed);
  const std::vector<SceneObject> t = s.thinned();
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].positions.size(), 77u);  // its share is 80 of the 100: every 13th of 1000
  EXPECT_LE(t[1].positions.size(), 20u);
  EXPECT_EQ(t[0].positions[1].x(), 13.0);
  const std::vector<std::string> notes = s.notes();
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("scan: 1000 points, "), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("limit 100 points per page"), std::string::npos) << notes[0];
}

TEST(ReportScene, MeshThinnedUnderTheLimitWithASubsetOfVertices) {
  const Mesh m = grid_mesh(200);  // 80000 triangles
  Scene::Limits limits;
  limits.max_triangles = 10000;
  Scene s(limits);
  s.add_mesh("reference", m, kGrey, 0.5);
  const SceneObject t = s.thinned()[0];
  EXPECT_LE(t.triangles.size(), 10000u);
  EXPECT_GE(t.triangles.size(), 2000u);  // not thinned away
  std::set<std::tuple<double, double, double>> input;
  for (const auto& v : m.vertices) input.insert({v.x(), v.y(), v.z()});
  for (const auto& v : t.positions) EXPECT_TRUE(input.count({v.x(), v.y(), v.z()}));
  for (const auto& tri : t.triangles) {
    for (auto i : tri) EXPECT_LT(i, t.positions.size());
  }
  EXPECT_EQ(s.notes().size(), 1u);
  Scene small;
  small.add_mesh("reference", m, kGrey);
  EXPECT_EQ(small.thinned()[0].triangles.size(), 80000u);
  EXPECT_TRUE(small.notes().empty());
}

TEST(ReportScene, RefusesMismatchedArraysAndDuplicateNames) {
  Scene s;
  EXPECT_THROW(s.add_points("a", {{0, 0, 0}}, std::vector<Rgb>{kRed, kRed}), std::invalid_argument);
  EXPECT_THROW(s.add_arrows("b", {{0, 0, 0}}, {}, 1.0, kRed), std::invalid_argument);
  EXPECT_THROW(s.add_mesh("c", {{0, 0, 0}}, {{0, 1, 2}}, kRed), std::invalid_argument);
  s.add_points("d", {{0, 0, 0}}, kRed);
  EXPECT_THROW(s.add_points("d", {{0, 0, 0}}, kRed), std::invalid_argument);
  s.add_arrows("e", {{0, 0, 0}, {1, 1, 1}}, {{0, 0, 2}, {0, 0, 0}}, 5.0, kRed);  // the zero direction is skipped
  EXPECT_EQ(s.objects().back().positions.size(), 1u);
  EXPECT_DOUBLE_EQ(s.objects().back().directions[0].z(), 1.0);
}

}  // namespace
}  // namespace conform::html
