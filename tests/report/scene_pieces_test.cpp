// Several lines in one layer (Scene::add_polylines): stored as segment pairs, thinned by whole segments.

#include "conform/report/scene.h"

#include <gtest/gtest.h>

namespace conform::html {
namespace {

TEST(ScenePieces, LinesBecomeSegmentPairsAndThinWhole) {
  Scene scene;
  const std::vector<std::vector<Eigen::Vector3d>> lines = {
      {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{5, 5, 0}}, {{0, 1, 0}, {0, 2, 0}}};
  const SceneObject& o = scene.add_polylines("paths", lines, kBlue);
  EXPECT_TRUE(o.pieces);
  EXPECT_EQ(o.kind, ObjectKind::kPolyline);
  // 2 segments of the first line, none of the single point, 1 of the last: 6 positions, in pairs.
  ASSERT_EQ(o.positions.size(), 6u);
  EXPECT_EQ(o.positions[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(o.positions[2], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(o.positions[5], Eigen::Vector3d(0, 2, 0));
  // Thinned to 2 items: every 3rd segment... (k = 3: segments 0 only), each kept whole.
  const SceneObject thin = thin_by_stride(o, 2);
  ASSERT_EQ(thin.positions.size(), 2u);
  EXPECT_EQ(thin.positions[0], Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(thin.positions[1], Eigen::Vector3d(1, 0, 0));
}

}  // namespace
}  // namespace conform::html
