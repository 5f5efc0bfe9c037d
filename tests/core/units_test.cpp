#include "conform/core/units.h"

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(Units, KnownUnitsInMillimetres) {
  EXPECT_EQ(millimetres_per_unit("mm"), 1.0);
  EXPECT_EQ(millimetres_per_unit("cm"), 10.0);
  EXPECT_EQ(millimetres_per_unit("M"), 1000.0);
  EXPECT_EQ(millimetres_per_unit("in"), 25.4);
}

TEST(Units, UnknownUnitNamesItAndTheAcceptedOnes) {
  try {
    millimetres_per_unit("furlong");
    FAIL() << "an unknown unit was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'furlong' (use mm, cm, m or in)"), std::string::npos) << e.what();
  }
}

TEST(Units, ScalingMovesPointsAndKeepsNormals) {
  Mesh mesh;
  mesh.vertices = {{0.001, 0.002, -0.5}};
  mesh.normals = {{0, 0, 1}};
  scale_in_place(mesh, 1000.0);
  EXPECT_LT((mesh.vertices[0] - Eigen::Vector3d(1, 2, -500)).norm(), 1e-12);
  EXPECT_EQ(mesh.normals[0], Eigen::Vector3d(0, 0, 1));

  Cloud cloud = to_cloud(mesh);
  scale_in_place(cloud, 0.5);
  EXPECT_FLOAT_EQ(cloud.points[0].z, -250.0f);
  EXPECT_THROW(scale_in_place(cloud, 0.0), Error);
  EXPECT_THROW(scale_in_place(cloud, -1.0), Error);
}

}  // namespace
}  // namespace conform
