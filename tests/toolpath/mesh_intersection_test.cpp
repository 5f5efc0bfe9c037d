// The mesh intersection on hard degenerate input: a square tube whose vertex ring lies exactly in a grid plane,
// with edges lying on the plane's grid lines; and the same rotated (inexact) at random. The welded curve must come
// out as one closed, simple loop every time.

#include "conform/toolpath/intersection/mesh_intersection.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "conform/core/error.h"
#include "conform/toolpath/intersection/azimuth_path.h"
#include "conform/toolpath/intersection/intersection_graph.h"

namespace conform {
namespace {

// A grid of the plane z = 0 over [-n, n]^2, unit squares split into two triangles each.
Mesh grid_plane(int n) {
  Mesh mesh;
  const int side = 2 * n + 1;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) mesh.vertices.emplace_back(i - n, j - n, 0.0);
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      const int v = j * side + i;
      mesh.faces.push_back({v, v + 1, v + side + 1});
      mesh.faces.push_back({v, v + side + 1, v + side});
    }
  return mesh;
}

// A square tube about the z axis, half-width h, rings at z = -2 .. 2 (the ring z = 0 lies exactly in the plane,
// and its edges run along the plane's grid lines), `per_side` vertices per side.
Mesh square_tube(int h, int per_side) {
  Mesh mesh;
  std::vector<Eigen::Vector2d> ring;
  for (int side = 0; side < 4; ++side) {
    for (int k = 0; k < per_side; ++k) {
      const double t = -h + 2.0 * h * k / per_side;
      const Eigen::Vector2d p[4] = {{t, -h}, {h, t}, {-t, h}, {-h, -t}};
      ring.push_back(p[side]);
    }
  }
  const int m = static_cast<int>(ring.size());
  for (int z = -2; z <= 2; ++z)
    for (const Eigen::Vector2d& p : ring) mesh.vertices.emplace_back(p.x(), p.y(), z);
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < m; ++k) {
      const int a = r * m + k;
      const int b = r * m + (k + 1) % m;
      mesh.faces.push_back({a, b, b + m});
      mesh.faces.push_back({a, b + m, a + m});
    }
  return mesh;
}

void expect_one_loop(const Mesh& a, const Mesh& b, const char* what) {
  const MeshIntersectionResult cut = intersect_meshes(a, b);
  EXPECT_EQ(cut.odd_pairs, 0u) << what;
  const IntersectionGraph graph = weld_segments(cut.segments);
  const CurveCheck check = check_intersection_graph(graph);
  ASSERT_TRUE(check.ok) << what << ": " << check.message;
  const AzimuthOrder order = order_by_azimuth(graph, 0.0);
  EXPECT_TRUE(order.check.ok) << what << ": " << order.check.message;
}

TEST(MeshIntersection, SquareTubeWithARingExactlyInTheGridPlaneGivesOneClosedLoop) {
  const Mesh plane = grid_plane(6);
  for (const int per_side : {2, 3, 4, 8}) {
    const Mesh tube = square_tube(2, per_side);
    expect_one_loop(plane, tube, "tube B, plane A");
    expect_one_loop(tube, plane, "plane B, tube A");
    // Every curve point on the tube's ring: exactly z = 0 and on the square |x| = 2 or |y| = 2.
    const IntersectionGraph graph = weld_segments(intersect_meshes(plane, tube).segments);
    for (const Eigen::Vector3d& p : graph.vertices) {
      EXPECT_EQ(p.z(), 0.0);
      EXPECT_NEAR(std::max(std::abs(p.x()), std::abs(p.y())), 2.0, 1e-15);
    }
  }
}

TEST(MeshIntersection, RandomlyRotatedDegenerateConfigurationsStillGiveOneClosedLoop) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> angle(-0.3, 0.3);
  for (int trial = 0; trial < 20; ++trial) {
    Mesh plane = grid_plane(6);
    const Mesh tube = square_tube(2, 1 + trial % 5);
    // Tilt the plane slightly about a random axis through the origin: rounding scatters its vertices around the
    // tube's ring, some exactly on it, some one ulp off.
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitX()) *
                               Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitY()))
                                  .toRotationMatrix();
    for (Eigen::Vector3d& v : plane.vertices) v = R * v;
    expect_one_loop(plane, tube, "tilted");
  }
}

TEST(MeshIntersection, DisjointMeshesGiveNoSegmentsAndMeshesWithoutFacesAreRejected) {
  Mesh tube = square_tube(2, 2);
  for (Eigen::Vector3d& v : tube.vertices) v.z() += 10.0;
  EXPECT_TRUE(intersect_meshes(grid_plane(3), tube).segments.empty());
  Mesh empty;
  empty.vertices.emplace_back(0, 0, 0);
  EXPECT_THROW(intersect_meshes(empty, tube), Error);
  MeshIntersectionOptions options;
  options.cell_mm = -1.0;
  EXPECT_THROW(intersect_meshes(grid_plane(3), tube, options), Error);
}

TEST(MeshIntersection, TheSegmentsDoNotDependOnTheGridCell) {
  const Mesh plane = grid_plane(6);
  const Mesh tube = square_tube(2, 3);
  MeshIntersectionOptions fine;
  fine.cell_mm = 0.3;
  MeshIntersectionOptions coarse;
  coarse.cell_mm = 5.0;
  const auto a = intersect_meshes(plane, tube, fine).segments;
  const auto b = intersect_meshes(plane, tube, coarse).segments;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].face_a, b[i].face_a);
    EXPECT_EQ(a[i].face_b, b[i].face_b);
    EXPECT_EQ(a[i].ends[0].point, b[i].ends[0].point);
  }
}

}  // namespace
}  // namespace conform
