// Which cylindrical CAD faces are one hole or boss (pipelines/src/inspect/inspect_feature_groups.h): the same axis,
// radius and side within the stated tolerances, and the merged nominal.

#include <gtest/gtest.h>

#include <vector>

#include "conform/core/cad_faces.h"
#include "inspect/inspect_feature_groups.h"

namespace conform {
namespace {

CadFace cylinder(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis, double radius, int sense,
                 const Eigen::Vector3d& centre, double area) {
  CadFace f;
  f.type = CadSurfaceType::kCylinder;
  f.origin_mm = origin;
  f.axis = axis.normalized();
  f.radius_mm = radius;
  f.sense = sense;
  f.centre_mm = centre;
  f.area_mm2 = area;
  f.triangles = 10;
  return f;
}

CadFace plane() {
  CadFace f;
  f.type = CadSurfaceType::kPlane;
  f.sense = 1;
  return f;
}

TEST(InspectFeatureGroups, FacesOnOneCylinderAreOneFeature) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  std::vector<CadFace> faces = {
      plane(),
      // 1, 3: the two halves of a hole R 6 at (20, 30), their axis points at different heights (the same axis).
      cylinder({20, 30, 5}, z, 6.0, -1, {20, 36, 10}, 200.0),
      plane(),
      cylinder({20, 30, 15}, -z, 6.0 + 2e-4, -1, {20, 24, 10}, 100.0),
      // 4: the same axis, a boss (the other side outside): another feature.
      cylinder({20, 30, 40}, z, 6.0, 1, {20, 36, 40}, 50.0),
      // 5: the same axis, radius 6.01: another feature.
      cylinder({20, 30, 0}, z, 6.01, -1, {20, 36, 0}, 50.0),
      // 6: parallel, 0.01 mm away: another feature.
      cylinder({20.01, 30, 0}, z, 6.0, -1, {20, 36, 0}, 50.0),
      // 7: through (20, 30) but tilted by 1e-4 rad: another feature.
      cylinder({20, 30, 0}, Eigen::Vector3d(1e-4, 0, 1), 6.0, -1, {20, 36, 0}, 50.0),
      // 8: a third part of the hole of 1 and 3, listed after the others.
      cylinder({20, 30, -3}, z, 6.0, -1, {14, 30, 10}, 100.0),
  };
  const std::vector<std::vector<std::size_t>> groups = detail::cylinder_features(faces);
  const std::vector<std::vector<std::size_t>> expected = {{1, 3, 8}, {4}, {5}, {6}, {7}};
  EXPECT_EQ(groups, expected);

  // The merged nominal: the first face's cylinder, the areas and triangles summed, the area-weighted centre, and the
  // axis point nearest it.
  const CadFace merged = detail::feature_nominal(faces, groups[0]);
  EXPECT_EQ(merged.type, CadSurfaceType::kCylinder);
  EXPECT_EQ(merged.radius_mm, 6.0);
  EXPECT_EQ(merged.sense, -1);
  EXPECT_DOUBLE_EQ(merged.area_mm2, 400.0);
  EXPECT_EQ(merged.triangles, 30u);
  const Eigen::Vector3d centre = (200.0 * Eigen::Vector3d(20, 36, 10) + 100.0 * Eigen::Vector3d(20, 24, 10) +
                                  100.0 * Eigen::Vector3d(14, 30, 10)) /
                                 400.0;
  EXPECT_LT((merged.centre_mm - centre).norm(), 1e-12);
  EXPECT_LT((merged.origin_mm - Eigen::Vector3d(20, 30, 10)).norm(), 1e-12);
}

TEST(InspectFeatureGroups, NoCylinderNoFeature) {
  EXPECT_TRUE(detail::cylinder_features({plane(), plane()}).empty());
  EXPECT_TRUE(detail::cylinder_features({}).empty());
}

}  // namespace
}  // namespace conform
