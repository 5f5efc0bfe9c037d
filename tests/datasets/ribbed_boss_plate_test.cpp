// The near-symmetric plate (datasets/ribbed_boss_plate.h): the boss's profile against its formula, the mesh's grid,
// heights and orientation against the plate's own height function.

#include "conform/datasets/ribbed_boss_plate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(RibbedBossPlate, BossIsFourMillimetresHighWithASmoothstepRamp) {
  EXPECT_DOUBLE_EQ(ribbed_plate_boss_height(-70.0, 45.0), 4.0);
  EXPECT_DOUBLE_EQ(ribbed_plate_boss_height(-62.0, 45.0), 4.0);  // 8 mm out: the ramp's top
  EXPECT_DOUBLE_EQ(ribbed_plate_boss_height(-61.0, 45.0), 2.0);  // half-way: smoothstep(1/2) = 1/2
  EXPECT_DOUBLE_EQ(ribbed_plate_boss_height(-70.0, 35.0), 0.0);  // 10 mm out
  EXPECT_DOUBLE_EQ(ribbed_plate_boss_height(70.0, -45.0), 0.0);  // the half-turned place: no boss
}

TEST(RibbedBossPlate, MeshIsTheHeightFieldOnItsGrid) {
  const RibbedPlateOptions o;  // 200 x 150 mm
  const Mesh mesh = ribbed_boss_plate_mesh(o, 2.0);
  ASSERT_EQ(mesh.vertices.size(), 101u * 76u);
  ASSERT_EQ(mesh.faces.size(), 2u * 100u * 75u);
  for (const Eigen::Vector3d& v : mesh.vertices) {
    ASSERT_DOUBLE_EQ(v.z(), ribbed_plate_height(o, v.x(), v.y()) + ribbed_plate_boss_height(v.x(), v.y()));
  }
  EXPECT_DOUBLE_EQ(mesh.vertices.front().x(), -100.0);
  EXPECT_DOUBLE_EQ(mesh.vertices.back().y(), 75.0);
  for (const Face& f : mesh.faces) {  // counter-clockwise from above: upward face normals
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(f[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(f[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(f[2])];
    ASSERT_GT((b - a).cross(c - a).z(), 0.0);
  }
  EXPECT_THROW(ribbed_boss_plate_mesh(o, 0.0), Error);
}

}  // namespace
}  // namespace conform
