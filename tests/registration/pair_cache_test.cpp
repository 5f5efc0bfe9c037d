// PairCache (registration/src/pair_cache.h): ICP's searches reused between iterations give exactly the searches'
// own answers, through motions that shrink like ICP's steps, and reuse most of them once the motion is small.

#include "pair_cache.h"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/nearest_neighbors.h"
#include "conform/core/triangle_index.h"
#include "conform/datasets/parts.h"

namespace conform {
namespace {

// Poses converging to the identity like ICP's: 3 deg and 5 mm off, each step leaving `rate` of the error.
std::vector<Eigen::Isometry3d> converging_poses(int count, double rate) {
  std::vector<Eigen::Isometry3d> poses;
  double f = 1.0;
  for (int k = 0; k < count; ++k, f *= rate) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(f * 3.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    T.translation() = f * Eigen::Vector3d(3.0, -4.0, 0.5);
    poses.push_back(T);
  }
  return poses;
}

TEST(PairCache, NearestPointsAreTheTreesThroughConvergingPoses) {
  PartOptions options;
  options.edge_mm = 5.0;
  const Mesh reference = box_part(options);
  options.edge_mm = 5.5;
  options.noise_mm = 0.02;
  const Mesh scan = box_part(options);
  const IcpReference icp_reference(reference);
  const KdTree& tree = icp_reference.tree();
  detail::PairCache cache;
  cache.reset(scan.vertices.size(), false);
  for (const Eigen::Isometry3d& T : converging_poses(16, 0.5)) {
    for (std::size_t i = 0; i < scan.vertices.size(); ++i) {
      const Eigen::Vector3f q = (T * scan.vertices[i]).cast<float>();
      const IcpReference::Sample* s = cache.nearest(icp_reference, i, q);
      ASSERT_NE(s, nullptr);
      const auto j = static_cast<std::size_t>(tree.nearest(q));
      ASSERT_EQ(s->point, icp_reference.points()[j]) << i;
      ASSERT_EQ(s->normal, icp_reference.normals()[j]) << i;
    }
  }
}

TEST(PairCache, ClosestSurfacePointsAreTheIndexsThroughConvergingPoses) {
  PartOptions options;
  options.edge_mm = 6.0;
  const Mesh reference = box_part(options);
  options.edge_mm = 5.0;
  options.noise_mm = 0.02;
  const Mesh scan = box_part(options);
  const TriangleIndex index(reference);
  detail::PairCache cache;
  for (double max_distance : {10.0, 0.05}) {
    cache.reset(scan.vertices.size(), true);
    for (const Eigen::Isometry3d& T : converging_poses(16, 0.5)) {
      for (std::size_t i = 0; i < scan.vertices.size(); ++i) {
        const Eigen::Vector3d q = T * scan.vertices[i];
        const SurfacePoint a = cache.closest(index, i, q, max_distance);
        const SurfacePoint b = index.closest(q, max_distance);
        ASSERT_EQ(a.face, b.face) << i;
        ASSERT_EQ(a.sq_distance, b.sq_distance) << i;
        ASSERT_EQ(a.feature, b.feature) << i;
      }
    }
  }
}

}  // namespace
}  // namespace conform
