// What the coarse stage of `conform align` sees of a reference mesh (pipelines/src/align/align_coarse_reference.h):
// the scan's spacing (its median nearest-neighbour gap) on a grid and on random points, and the reference sampled at
// it by area.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "align/align_coarse_reference.h"
#include "conform/core/error.h"
#include "conform/core/mesh.h"
#include "conform/core/random.h"

namespace conform::detail {
namespace {

// A tilted plane: a point's (u, v) on it in mm.
Eigen::Vector3d on_plane(double u, double v) {
  const Eigen::Vector3d a = Eigen::Vector3d(1.0, 0.2, 0.3).normalized();
  const Eigen::Vector3d b = a.cross(Eigen::Vector3d(0.1, 0.3, 1.0)).normalized();
  return Eigen::Vector3d(5.0, -3.0, 2.0) + u * a + v * b;
}

TEST(AlignCoarseReference, SpacingOfAGridIsItsPitch) {
  // 200 x 200 points 0.4 mm apart: every nearest gap is the pitch.
  std::vector<Eigen::Vector3d> grid;
  for (int i = 0; i < 200; ++i) {
    for (int j = 0; j < 200; ++j) grid.push_back(on_plane(0.4 * i, 0.4 * j));
  }
  EXPECT_NEAR(scan_spacing(grid), 0.4, 1e-5);
}

TEST(AlignCoarseReference, SpacingOfRandomPointsIsTheirMedianGap) {
  // 40 000 points at random on 80 x 80 mm, 6.25 a mm^2: a point has no other within r with probability
  // exp(-6.25 pi r^2), so the median nearest gap is sqrt(ln 2 / (6.25 pi)) = 0.1879 mm (the grid of that density:
  // 0.4 mm, and a reference sampled at the gap has 4.5 times the scan's density). The median of 500 sampled gaps is
  // within ~4 % (one std) of it.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    Random random(seed);
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < 40000; ++i) points.push_back(on_plane(random.uniform(0.0, 80.0), random.uniform(0.0, 80.0)));
    EXPECT_NEAR(scan_spacing(points), std::sqrt(std::log(2.0) / (6.25 * M_PI)), 0.1 * 0.1879) << "seed " << seed;
  }
}

TEST(AlignCoarseReference, TooFewPointsHaveNoSpacing) {
  EXPECT_EQ(scan_spacing({}), 0.0);
  EXPECT_EQ(scan_spacing({Eigen::Vector3d::Zero()}), 0.0);
  // Two points: their one gap.
  EXPECT_NEAR(scan_spacing({Eigen::Vector3d::Zero(), Eigen::Vector3d(0.0, 0.0, 2.0)}), 2.0, 1e-6);
}

TEST(AlignCoarseReference, SamplesTheSurfaceByAreaAtTheSpacing) {
  // Two triangles, 60 x 40 mm: 2400 mm^2 at 0.5 mm is 9600 points, on the plane, with its normal.
  Mesh mesh;
  mesh.vertices = {on_plane(0, 0), on_plane(60, 0), on_plane(60, 40), on_plane(0, 40)};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}};
  const Mesh sample = coarse_reference(mesh, 0.5);
  ASSERT_NEAR(static_cast<double>(sample.vertices.size()), 9600.0, 1.0);
  ASSERT_EQ(sample.normals.size(), sample.vertices.size());
  const Eigen::Vector3d n = (mesh.vertices[1] - mesh.vertices[0]).cross(mesh.vertices[3] - mesh.vertices[0]).normalized();
  for (std::size_t i = 0; i < sample.vertices.size(); ++i) {
    EXPECT_NEAR((sample.vertices[i] - mesh.vertices[0]).dot(n), 0.0, 1e-9);
    EXPECT_NEAR(std::abs(sample.normals[i].dot(n)), 1.0, 1e-9);
  }
  // At most kCoarseReferenceMaxPoints, at least 1000.
  EXPECT_EQ(coarse_reference(mesh, 0.01).vertices.size(), kCoarseReferenceMaxPoints);
  EXPECT_EQ(coarse_reference(mesh, 50.0).vertices.size(), 1000u);
  EXPECT_THROW(coarse_reference(mesh, 0.0), Error);
}

}  // namespace
}  // namespace conform::detail
