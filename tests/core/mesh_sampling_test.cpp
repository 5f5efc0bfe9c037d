// sample_mesh_surface: shares by area, points on their faces (or on the smooth surface), the same points every call.

#include "conform/core/mesh_sampling.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "test_meshes.h"

namespace conform {
namespace {

using V = Eigen::Vector3d;

// Three triangles of a 4 x 1 mm rectangle: areas 0.5, 1.5 and 2 mm^2. Of 20,000
// points each gets its share within 0.1 % (a low-discrepancy sequence: a random draw would be off by ~0.3 %), every
// point inside its face, the face's normal +z, and a second call gives the same points.
TEST(MeshSampling, SharesFollowTheAreas) {
  Mesh m;
  m.vertices = {V(0, 0, 0), V(1, 0, 0), V(4, 1, 0), V(0, 1, 0), V(4, 0, 0)};
  m.faces = {{0, 1, 3}, {1, 4, 2}, {1, 2, 3}};  // 0.5, 1.5 and 2 mm^2
  const MeshSurfaceSample s = sample_mesh_surface(m, 20000);
  ASSERT_EQ(s.points.size(), 20000u);
  std::size_t counts[3] = {0, 0, 0};
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto f = static_cast<std::size_t>(s.faces[i]);
    ++counts[f];
    const V& a = m.vertices[static_cast<std::size_t>(m.faces[f][0])];
    const V& b = m.vertices[static_cast<std::size_t>(m.faces[f][1])];
    const V& c = m.vertices[static_cast<std::size_t>(m.faces[f][2])];
    const V& p = s.points[i];
    ASSERT_EQ(p.z(), 0.0);
    for (const auto& [u, v] : {std::make_pair(a, b), std::make_pair(b, c), std::make_pair(c, a)}) {
      ASSERT_GE((v - u).cross(p - u).z(), -1e-12) << i;  // left of every edge: inside
    }
    ASSERT_EQ(s.normals[i], V(0, 0, 1));
  }
  EXPECT_NEAR(static_cast<double>(counts[0]) / 20000.0, 0.5 / 4.0, 0.001);
  EXPECT_NEAR(static_cast<double>(counts[1]) / 20000.0, 1.5 / 4.0, 0.001);
  EXPECT_NEAR(static_cast<double>(counts[2]) / 20000.0, 2.0 / 4.0, 0.001);
  EXPECT_EQ(sample_mesh_surface(m, 20000).points, s.points);
}

// The face of the k-th point is where the sequence's first coordinate, frac(1/2 + k / g) of the total area, falls in
// the faces' cumulative areas (g the real root of g^4 = g + 1): checked for every point of a 50,000-point sample of
// a sphere's 576 facets of unequal areas with two faces of no area among them (which get no point).
TEST(MeshSampling, EachPointsFaceIsWhereItsPickFalls) {
  Mesh sphere = test::lat_long_sphere(12, 24, [](double, double) { return 20.0; });
  const int degenerate = static_cast<int>(sphere.vertices.size());
  sphere.vertices.push_back(V(1, 1, 1));
  sphere.faces.insert(sphere.faces.begin() + 7, {degenerate, degenerate, degenerate});
  sphere.faces.push_back({degenerate, degenerate, degenerate});
  std::vector<double> cumulative;
  double total = 0.0;
  for (const Face& f : sphere.faces) {
    const V& a = sphere.vertices[static_cast<std::size_t>(f[0])];
    total += (sphere.vertices[static_cast<std::size_t>(f[1])] - a)
                 .cross(sphere.vertices[static_cast<std::size_t>(f[2])] - a)
                 .norm();
    cumulative.push_back(total);
  }
  const double g = 1.2207440846057594753616853491088319144324890862486;
  const MeshSurfaceSample s = sample_mesh_surface(sphere, 50000);
  for (std::size_t k = 0; k < s.faces.size(); ++k) {
    const double x = 0.5 + static_cast<double>(k) / g;
    const double pick = (x - std::floor(x)) * total;
    const auto f = static_cast<std::size_t>(s.faces[k]);
    ASSERT_GT(cumulative[f], pick) << k;
    if (f > 0) {
      ASSERT_LE(cumulative[f - 1], pick) << k;
    }
    ASSERT_NE(f, 7u) << k;
  }
}

// On a sphere's smooth surface (R 20, 12 x 24 facets, 0.34 mm chord error): the points lie on the sphere within
// 0.011 mm, their normals radial within 1 deg.
TEST(MeshSampling, OnTheSmoothSurface) {
  const Mesh sphere = test::lat_long_sphere(12, 24, [](double, double) { return 20.0; });
  const PhongSurface smooth(sphere);
  const MeshSurfaceSample s = sample_mesh_surface(sphere, 5000, &smooth);
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    ASSERT_NEAR(s.points[i].norm(), 20.0, 0.011) << i;
    ASSERT_GT(s.normals[i].dot(s.points[i].normalized()), std::cos(M_PI / 180.0)) << i;
  }
}

TEST(MeshSampling, BadInputIsAnError) {
  Mesh flat;
  flat.vertices = {V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)};
  flat.faces = {{0, 1, 2}};
  EXPECT_THROW(sample_mesh_surface(flat, 10), Error);  // no area
  flat.vertices[2] = V(0, 1, 0);
  EXPECT_THROW(sample_mesh_surface(flat, 0), Error);
  flat.faces = {{0, 1, 5}};
  EXPECT_THROW(sample_mesh_surface(flat, 10), Error);
}

}  // namespace
}  // namespace conform
