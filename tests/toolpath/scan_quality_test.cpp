// The scan measures near the seam against generated tubes whose noise, edge length and radius are known.

#include "conform/toolpath/intersection/scan_quality.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/datasets/tube.h"

namespace conform {
namespace {

TubeScan tube(double noise_mm) {
  TubeOptions t;
  t.radius_mm = 300.0;
  t.length_mm = 200.0;
  t.arc_rad = 1.0;
  t.edge_mm = 4.0;
  t.noise_mm = noise_mm;
  t.seed = 3;
  return generate_tube(t);
}

std::vector<Eigen::Vector3d> samples(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = mesh.vertices.size() / 4; i < mesh.vertices.size() * 3 / 4; i += 97)
    points.push_back(mesh.vertices[i]);
  return points;
}

TEST(ScanQuality, NoiseEdgeAndCurvatureOfAGeneratedTube) {
  const TubeScan clean = tube(0.0);
  const ScanQuality q = estimate_scan_quality(clean.mesh, samples(clean.mesh));
  EXPECT_GT(q.samples, 20u);
  EXPECT_LT(q.noise_mm, 0.01);  // the facets of a 4 mm mesh on R 300 lie within 0.007 mm of the cylinder
  EXPECT_NEAR(q.curvature_per_mm, 1.0 / 300.0, 0.05 / 300.0);
  EXPECT_GT(q.edge_mm, 3.5);
  EXPECT_LT(q.edge_mm, 5.0);
  EXPECT_NEAR(q.edge_angle_deg, q.edge_mm / 300.0 * 180.0 / 3.141592653589793, 0.05);
  const TubeScan noisy = tube(0.2);
  const ScanQuality n = estimate_scan_quality(noisy.mesh, samples(noisy.mesh));
  EXPECT_NEAR(n.noise_mm, 0.2, 0.03);
}

TEST(ScanQuality, CrossingSineOfTwoSurfaces) {
  ScanQuality a;
  ScanQuality b;
  a.normals = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX()};
  b.normals = {Eigen::Vector3d::UnitY(), Eigen::Vector3d(std::cos(0.3), std::sin(0.3), 0.0)};
  EXPECT_NEAR(min_crossing_sine(a, b), std::sin(0.3), 1e-12);
}

}  // namespace
}  // namespace conform
