// Mesh boundaries: a grid with a square hole has two closed loops (rim and hole) of known length and winding; a
// strip is one loop; a closed surface has none; two holes touching at a vertex give open chains cut there.

#include "conform/core/mesh_boundary.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "test_meshes.h"

namespace conform {
namespace {

// An n x n grid of unit cells in the z = 0 plane, faces counter-clockwise from +z, without the cells for which
// `skip(i, j)` is true.
template <typename Skip>
Mesh grid(int n, Skip skip) {
  Mesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i, j, 0.0);
  }
  const auto v = [n](int i, int j) { return static_cast<std::int32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (skip(i, j)) continue;
      m.faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      m.faces.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  }
  return m;
}

// Signed area of a polyline's projection on z = 0 (shoelace): > 0 counter-clockwise.
double signed_area(const Polyline& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    const Eigen::Vector3d& u = p.points[i];
    const Eigen::Vector3d& w = p.points[(i + 1) % p.points.size()];
    a += u.x() * w.y() - w.x() * u.y();
  }
  return 0.5 * a;
}

TEST(MeshBoundary, GridWithAHoleHasTheRimAndTheHole) {
  const Mesh m = grid(6, [](int i, int j) { return i >= 2 && i < 4 && j >= 2 && j < 4; });
  const std::vector<Polyline> loops = boundary_polylines(m);
  ASSERT_EQ(loops.size(), 2u);
  // Exact: unit edges, the rim 4 x 6, the hole 4 x 2; the rim starts at vertex 0 so it comes first.
  EXPECT_TRUE(loops[0].closed);
  EXPECT_TRUE(loops[1].closed);
  EXPECT_DOUBLE_EQ(length(loops[0]), 24.0);
  EXPECT_DOUBLE_EQ(length(loops[1]), 8.0);
  EXPECT_EQ(loops[0].points.size(), 24u);
  EXPECT_EQ(loops[1].points.size(), 8u);
  // The surface lies to the left of the walk: the rim runs counter-clockwise, the hole clockwise.
  EXPECT_DOUBLE_EQ(signed_area(loops[0]), 36.0);
  EXPECT_DOUBLE_EQ(signed_area(loops[1]), -4.0);
  const std::vector<std::vector<int>> indices = boundary_loops(m);
  ASSERT_EQ(indices.size(), 2u);
  EXPECT_EQ(indices[0].front(), 0);
}

TEST(MeshBoundary, ClosedSurfaceHasNoBoundary) {
  EXPECT_TRUE(boundary_polylines(test::lat_long_sphere(12, 24, [](double, double) { return 10.0; })).empty());
}

TEST(MeshBoundary, HolesTouchingAtAVertexAreCutIntoOpenChains) {
  // Two removed cells meeting only at the vertex (3, 3): that vertex has two boundary edges in and two out.
  const Mesh m = grid(6, [](int i, int j) { return (i == 2 && j == 2) || (i == 3 && j == 3); });
  const std::vector<Polyline> loops = boundary_polylines(m);
  std::size_t open = 0;
  double hole_length = 0.0;
  for (const Polyline& p : loops) {
    if (!p.closed) {
      ++open;
      hole_length += length(p);
      EXPECT_EQ(p.points.front(), Eigen::Vector3d(3, 3, 0));  // chains start and end at the shared vertex
      EXPECT_EQ(p.points.back(), Eigen::Vector3d(3, 3, 0));
    }
  }
  EXPECT_EQ(open, 2u);
  EXPECT_DOUBLE_EQ(hole_length, 8.0);  // both unit squares' perimeters
  EXPECT_EQ(loops.size(), 3u);         // plus the rim
}

TEST(MeshBoundary, BadInputThrows) {
  Mesh m = grid(2, [](int, int) { return false; });
  m.faces.push_back({0, 1, 99});
  EXPECT_THROW(boundary_polylines(m), Error);
  Mesh n = grid(2, [](int, int) { return false; });
  n.vertices[0].x() = std::nan("");
  EXPECT_THROW(boundary_polylines(n), Error);
}

}  // namespace
}  // namespace conform
