#include "conform/core/geometry.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/z_order.h"

namespace conform {
namespace {

Mesh unit_right_triangle() {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}};
  mesh.faces = {{0, 1, 2}};
  return mesh;
}

TEST(Geometry, BoundingBoxAndCentroidSkipNonFinitePoints) {
  Cloud cloud;
  cloud.points.push_back({1, 2, 3});
  cloud.points.push_back({-1, 5, 0});
  cloud.points.push_back({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  const BoundingBox box = bounding_box(cloud);
  EXPECT_EQ(box.min, Eigen::Vector3d(-1, 2, 0));
  EXPECT_EQ(box.max, Eigen::Vector3d(1, 5, 3));
  EXPECT_EQ(count_non_finite(cloud), 1u);
  EXPECT_TRUE(centroid(cloud).isApprox(Eigen::Vector3d(0, 3.5, 1.5), 1e-12));
  const std::vector<Eigen::Vector3d> points{{1, 2, 3}, {-1, 5, 0}, {std::numeric_limits<double>::infinity(), 0, 0}};
  EXPECT_TRUE(centroid(points).isApprox(Eigen::Vector3d(0, 3.5, 1.5), 1e-12));
}

TEST(Geometry, EmptyInputsSayWhatIsWrong) {
  EXPECT_TRUE(bounding_box(Cloud{}).empty());
  EXPECT_EQ(bounding_box(Cloud{}).size(), Eigen::Vector3d::Zero());
  EXPECT_THROW(centroid(Cloud{}), Error);
  EXPECT_THROW(centroid(std::vector<Eigen::Vector3d>{}), Error);
}

TEST(Geometry, TransformMovesPointsAndRotatesNormals) {
  Mesh mesh = unit_right_triangle();
  mesh.normals = vertex_normals_from_faces(mesh);
  Eigen::Isometry3d T_b_a = Eigen::Isometry3d::Identity();
  T_b_a.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T_b_a.translation() = Eigen::Vector3d(10, 20, 30);
  const Mesh moved = transformed(mesh, T_b_a);
  EXPECT_LT((moved.vertices[1] - Eigen::Vector3d(12, 20, 30)).norm(), 1e-12);
  EXPECT_LT((moved.vertices[2] - Eigen::Vector3d(10, 20, 33)).norm(), 1e-12);
  EXPECT_LT((moved.normals[0] - Eigen::Vector3d(0, -1, 0)).norm(), 1e-12);  // +z turned about x by 90 degrees

  const Cloud cloud_b = transformed(to_cloud(mesh), T_b_a);
  EXPECT_LT((cloud_b.points[1].getVector3fMap() - Eigen::Vector3f(12, 20, 30)).norm(), 1e-5f);
  EXPECT_LT((cloud_b.normals[0].getNormalVector3fMap() - Eigen::Vector3f(0, -1, 0)).norm(), 1e-6f);

  Polyline line{{{0, 0, 0}, {1, 0, 0}}, false};
  EXPECT_LT((transformed(line, T_b_a).points[1] - Eigen::Vector3d(11, 20, 30)).norm(), 1e-12);
}

// A turn of 0.1 rad about z through the origin moves a point at radius r by 2 r sin(0.05); a pure shift moves all
// points alike. The farthest point decides.
TEST(Geometry, LargestDisplacementIsTheFarthestPointsMotion) {
  const std::vector<Eigen::Vector3d> points = {{1, 0, 0}, {0, 3, 5}, {-2, 0, 1}};
  const Eigen::Isometry3d turn(Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(largest_displacement(points, Eigen::Isometry3d::Identity(), turn), 6.0 * std::sin(0.05), 1e-12);
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation() = Eigen::Vector3d(0.3, -0.4, 0.0);
  EXPECT_NEAR(largest_displacement(points, shift, Eigen::Isometry3d::Identity()), 0.5, 1e-12);
  EXPECT_EQ(largest_displacement({}, shift, turn), 0.0);
}

TEST(Mesh, AreasAndNormalsOfAKnownTriangle) {
  const Mesh mesh = unit_right_triangle();
  EXPECT_DOUBLE_EQ(face_area(mesh, 0), 3.0);
  EXPECT_DOUBLE_EQ(surface_area(mesh), 3.0);
  EXPECT_EQ(face_normal(mesh, 0), Eigen::Vector3d(0, 0, 1));
  for (const Eigen::Vector3d& n : vertex_normals_from_faces(mesh)) EXPECT_EQ(n, Eigen::Vector3d(0, 0, 1));
}

TEST(Mesh, DegenerateFaceHasZeroNormal) {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  mesh.faces = {{0, 1, 2}};
  EXPECT_EQ(face_normal(mesh, 0), Eigen::Vector3d::Zero());
  EXPECT_EQ(face_area(mesh, 0), 0.0);
}

// Two triangles sharing the edge 1-2 and a vertex no face uses: each vertex lists its faces, ascending.
TEST(Mesh, FacesAroundEachVertex) {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {5, 5, 5}};
  mesh.faces = {{0, 1, 2}, {1, 3, 2}};
  const VertexFaces rows = faces_around_vertices(mesh);
  EXPECT_EQ(rows.start, (std::vector<std::size_t>{0, 1, 3, 5, 6, 6}));
  EXPECT_EQ(rows.faces, (std::vector<std::size_t>{0, 0, 1, 0, 1, 1}));
}

TEST(Mesh, ConsistencyCheckNamesTheProblem) {
  Mesh mesh = unit_right_triangle();
  mesh.faces.push_back({0, 1, 7});
  try {
    check_consistent(mesh, "part.ply");
    FAIL() << "an out-of-range face was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("part.ply: face 1 refers to vertex 7 of 3"), std::string::npos) << e.what();
  }
}

TEST(Mesh, CloudConversionKeepsPointsAndNormals) {
  Mesh mesh = unit_right_triangle();
  mesh.normals = vertex_normals_from_faces(mesh);
  const Mesh back = to_mesh(to_cloud(mesh));
  ASSERT_EQ(back.vertices.size(), 3u);
  ASSERT_EQ(back.normals.size(), 3u);
  EXPECT_TRUE(back.faces.empty());
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.vertices[i], mesh.vertices[i]);  // small integers are exact in float
    EXPECT_EQ(back.normals[i], mesh.normals[i]);
  }
}

TEST(Polyline, LengthCountsTheClosingSegment) {
  Polyline square{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, false};
  EXPECT_DOUBLE_EQ(length(square), 3.0);
  square.closed = true;
  EXPECT_DOUBLE_EQ(length(square), 4.0);
}

// The eight corners of a cube, shuffled: a Z-curve visits them in the order of their Morton codes x + 2y + 4z; a
// duplicate follows its twin (ties keep index order) and a non-finite point comes last.
TEST(ZOrder, VisitsCubeCornersInMortonOrder) {
  const std::vector<int> shuffled = {5, 2, 7, 0, 3, 6, 1, 4};  // Morton code of each point
  std::vector<Eigen::Vector3d> points;
  for (int code : shuffled) points.emplace_back(10.0 + (code & 1), -3.0 + (code >> 1 & 1), 0.5 * (code >> 2 & 1));
  points.push_back(points[2]);  // code 7 again, index 8
  points.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  const std::vector<std::size_t> order = z_order(points);
  const std::vector<std::size_t> expected = {3, 6, 1, 4, 7, 0, 5, 2, 8, 9};
  EXPECT_EQ(order, expected);
  EXPECT_TRUE(z_order({}).empty());
}

// On random points the order is a permutation, and consecutive points are close: the mean step along it is a small
// fraction of the mean distance between random pairs (for n uniform points in a cube of side L, a Z-curve's mean
// step is of the order of the spacing L n^(-1/3); a random pair's about 0.66 L).
TEST(ZOrder, IsAPermutationWithShortSteps) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  std::vector<Eigen::Vector3d> points(20000);
  for (Eigen::Vector3d& p : points) p = Eigen::Vector3d(u(rng), u(rng), u(rng));
  const std::vector<std::size_t> order = z_order(points);
  ASSERT_EQ(order.size(), points.size());
  std::vector<bool> seen(points.size(), false);
  for (std::size_t i : order) {
    ASSERT_LT(i, points.size());
    ASSERT_FALSE(seen[i]);
    seen[i] = true;
  }
  double along = 0.0, random = 0.0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    along += (points[order[k]] - points[order[k - 1]]).norm();
    random += (points[k] - points[k - 1]).norm();
  }
  EXPECT_LT(along, 0.1 * random);  // spacing 100 / 20000^(1/3) = 3.7 mm against ~66 mm: measured ratio below
}

}  // namespace
}  // namespace conform
