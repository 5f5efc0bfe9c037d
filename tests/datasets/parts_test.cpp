// The box part and the free-form surface (datasets/parts.h): closed and outward (the divergence theorem gives the
// analytic volume), on their documented shape, meshed at the edge length, noise seeded and along the normals.

#include "conform/datasets/parts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/geometry.h"

namespace conform {
namespace {

// sum over faces of a . (b x c) / 6: the enclosed volume when the faces close the surface and point outwards.
double signed_volume(const Mesh& mesh) {
  double v = 0.0;
  for (const Face& f : mesh.faces) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    v += a.dot(mesh.vertices[static_cast<std::size_t>(f[1])].cross(mesh.vertices[static_cast<std::size_t>(f[2])]));
  }
  return v / 6.0;
}

double longest_edge(const Mesh& mesh) {
  double longest = 0.0;
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(f[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::size_t>(f[static_cast<std::size_t>((k + 1) % 3)]);
      longest = std::max(longest, (mesh.vertices[a] - mesh.vertices[b]).norm());
    }
  }
  return longest;
}

TEST(BoxPart, IsClosedOutwardAndOfTheDocumentedShape) {
  for (double edge : {10.0, 4.0, 2.5}) {
    PartOptions options;
    options.edge_mm = edge;
    const Mesh mesh = box_part(options);
    check_consistent(mesh, "box part");
    EXPECT_NEAR(signed_volume(mesh), kBoxPartVolumeMm3, 1e-6) << "edge " << edge;
    const BoundingBox box = bounding_box(mesh);
    EXPECT_EQ(box.min, Eigen::Vector3d(-90, -40, 0));
    EXPECT_EQ(box.max, Eigen::Vector3d(90, 40, 45));
    // A rectangle's cell diagonal is at most sqrt(2) edges; the chamfer's sheared cells are cut along their shorter
    // diagonal.
    EXPECT_LE(longest_edge(mesh), 1.5 * edge);
    EXPECT_EQ(mesh.normals.size(), mesh.vertices.size());
    // No vertex twice: facets are welded along their shared edges.
    std::vector<std::array<double, 3>> keys;
    for (const Eigen::Vector3d& v : mesh.vertices) keys.push_back({v.x(), v.y(), v.z()});
    std::sort(keys.begin(), keys.end());
    EXPECT_EQ(std::adjacent_find(keys.begin(), keys.end()), keys.end());
  }
}

TEST(FreeformSurface, LiesOnItsHeightFunctionWithUpwardFaces) {
  PartOptions options;
  options.edge_mm = 5.0;
  const Mesh mesh = freeform_surface(options);
  ASSERT_EQ(mesh.vertices.size(), 41u * 31u);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices[i];
    ASSERT_EQ(v.z(), freeform_height(v.x(), v.y()));
    // The stored normal is the height field's: perpendicular to its finite-difference tangents.
    const double h = 1e-5;
    const Eigen::Vector3d tx(2 * h, 0, freeform_height(v.x() + h, v.y()) - freeform_height(v.x() - h, v.y()));
    const Eigen::Vector3d ty(0, 2 * h, freeform_height(v.x(), v.y() + h) - freeform_height(v.x(), v.y() - h));
    EXPECT_NEAR(mesh.normals[i].dot(tx.cross(ty).normalized()), 1.0, 1e-9);
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) ASSERT_GT(face_normal(mesh, f).z(), 0.0);
  const BoundingBox box = bounding_box(mesh);
  EXPECT_EQ(box.min.head<2>(), Eigen::Vector2d(-100, -75));
  EXPECT_EQ(box.max.head<2>(), Eigen::Vector2d(100, 75));
}

TEST(Parts, NoiseIsSeededAndAlongTheNormals) {
  PartOptions clean;
  clean.edge_mm = 6.0;
  PartOptions noisy = clean;
  noisy.noise_mm = 0.1;
  noisy.seed = 9;
  for (auto make : {&box_part, &freeform_surface}) {
    const Mesh a = make(clean), b = make(noisy), c = make(noisy);
    ASSERT_EQ(a.vertices.size(), b.vertices.size());
    EXPECT_EQ(b.vertices, c.vertices);  // same seed, same bytes
    double sum_sq = 0.0;
    for (std::size_t i = 0; i < a.vertices.size(); ++i) {
      const Eigen::Vector3d d = b.vertices[i] - a.vertices[i];
      EXPECT_LT((d - d.dot(a.normals[i]) * a.normals[i]).norm(), 1e-12);
      sum_sq += d.squaredNorm();
    }
    EXPECT_NEAR(std::sqrt(sum_sq / static_cast<double>(a.vertices.size())), 0.1, 0.01);
  }
}

TEST(Parts, BadOptionsThrow) {
  PartOptions options;
  options.edge_mm = 0.0;
  EXPECT_THROW(box_part(options), Error);
  options.edge_mm = 0.001;  // billions of triangles
  EXPECT_THROW(freeform_surface(options), Error);
  options.edge_mm = 4.0;
  options.noise_mm = -1.0;
  EXPECT_THROW(box_part(options), Error);
}

}  // namespace
}  // namespace conform
