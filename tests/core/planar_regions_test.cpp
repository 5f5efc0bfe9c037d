// planar_faces against meshes whose planes are known: a CAD-like filleted block (flat sides between tangent fillets,
// fanned caps), a tessellated cylinder (coplanar strip pairs that are chords, not planes), a sphere, a scanner-like
// noisy plane, and the block in shop coordinates stored as floats.

#include "conform/core/planar_regions.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "test_meshes.h"

namespace conform {
namespace {

constexpr double kCrease = 30.0 * kPi / 180.0;

// Faces of filleted_block: four per outline segment (side lower, side upper, bottom cap, top cap); segment k of
// corner c is a fillet strip for k < chords, the flat side for k == chords.
void expect_block_planes(const Mesh& block, int chords, const std::vector<unsigned char>& flat) {
  ASSERT_EQ(flat.size(), block.faces.size());
  const int segments = 4 * (chords + 1);
  for (int s = 0; s < segments; ++s) {
    const bool side_is_flat = s % (chords + 1) == chords;
    for (int j = 0; j < 2; ++j) {
      EXPECT_EQ(flat[static_cast<std::size_t>(4 * s + j)], side_is_flat ? 1 : 0) << "segment " << s;
    }
    EXPECT_EQ(flat[static_cast<std::size_t>(4 * s + 2)], 1) << "bottom cap " << s;
    EXPECT_EQ(flat[static_cast<std::size_t>(4 * s + 3)], 1) << "top cap " << s;
  }
}

TEST(PlanarFaces, FlatSidesOfAFilletedBlockArePlanesItsFilletsAreNot) {
  for (int chords : {4, 32}) {
    const Mesh block = test::filleted_block(40, 30, 20, 10, chords);
    expect_block_planes(block, chords, planar_faces(block, kCrease));
  }
}

// The same block 5 m from the origin, rounded to float as an STL stores it: still the same planes.
TEST(PlanarFaces, ShopCoordinatesInFloatKeepThePlanes) {
  Mesh block = test::filleted_block(40, 30, 20, 10, 32);
  for (Eigen::Vector3d& v : block.vertices) {
    v = (v + Eigen::Vector3d(4850.25, -3120.5, 1210.75)).cast<float>().cast<double>();
  }
  expect_block_planes(block, 32, planar_faces(block, kCrease));
}

// A cylinder of radius 10 in 32 strips, each strip two coplanar triangles: chords of a curved surface, not planes.
// Its fanned caps are planes.
TEST(PlanarFaces, CylinderStripsAreNotPlanes) {
  const int chords = 8;
  const Mesh prism = test::filleted_block(20, 20, 30, 10, chords);  // a round prism: the fillets meet, no flat side
  const std::vector<unsigned char> flat = planar_faces(prism, kCrease);
  for (std::size_t s = 0; s < flat.size() / 4; ++s) {
    // The outline's segments between two corners have no length here: their four faces have no area, no plane.
    const bool degenerate = s % (chords + 1) == chords;
    EXPECT_EQ(flat[4 * s], 0) << s;
    EXPECT_EQ(flat[4 * s + 1], 0) << s;
    EXPECT_EQ(flat[4 * s + 2], degenerate ? 0 : 1) << s;
    EXPECT_EQ(flat[4 * s + 3], degenerate ? 0 : 1) << s;
  }
}

TEST(PlanarFaces, ASphereHasNoPlane) {
  const Mesh sphere = test::lat_long_sphere(12, 24, [](double, double) { return 20.0; });
  for (unsigned char f : planar_faces(sphere, kCrease)) EXPECT_EQ(f, 0);
}

// A 20 x 20 grid of 1 mm squares: exact, every face is on the plane (its inner vertices have flat fans); with
// 0.01 mm of noise, as a scanner's mesh, no two faces are coplanar and none is a plane.
TEST(PlanarFaces, ExactGridIsAPlaneNoisyGridIsNot) {
  for (double noise : {0.0, 0.01}) {
    std::mt19937_64 rng(3);
    std::normal_distribution<double> g(0.0, noise > 0 ? noise : 1.0);
    Mesh grid;
    const int n = 20;
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) grid.vertices.emplace_back(i, j, noise > 0 ? g(rng) : 0.0);
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const std::int32_t a = i * (n + 1) + j, b = a + n + 1;
        grid.faces.push_back({a, b, b + 1});
        grid.faces.push_back({a, b + 1, a + 1});
      }
    }
    std::size_t planes = 0;
    for (unsigned char f : planar_faces(grid, kCrease)) planes += f;
    EXPECT_EQ(planes, noise > 0 ? 0u : grid.faces.size()) << noise;
  }
}

TEST(PlanarFaces, RejectsAFaceIndexOutOfRange) {
  Mesh tri;
  tri.vertices = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)};
  tri.faces = {{0, 1, 3}};
  EXPECT_THROW(planar_faces(tri, kCrease), Error);
}

}  // namespace
}  // namespace conform
