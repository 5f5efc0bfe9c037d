// The deviation to the smooth surface (DeviationOptions::smooth_surface, the default) against generated meshes with
// an analytic surface: points sampled on the exact surface and offset by Gaussian noise along its normal must deviate
// by their noise (mean and std within 0.001 mm), where the flat facets are off by their chord error; flat parts and
// sharp edges measure exactly as the flat facets do.

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "conform/datasets/parts.h"
#include "conform/datasets/tube.h"
#include "conform/evaluation/deviation.h"
#include "conform/evaluation/statistics.h"

namespace conform {
namespace {

using V = Eigen::Vector3d;

struct Sample {
  std::vector<V> points;
  std::vector<double> offset_mm;
};

// Mean and population std by evaluation's own statistics; every value must be a matched point's.
DeviationStatistics moments(const std::vector<double>& v) {
  const DeviationStatistics s = deviation_statistics(v);
  EXPECT_EQ(s.excluded, 0u);
  return s;
}

DeviationResult deviation(const Sample& s, const Mesh& reference, bool smooth) {
  DeviationOptions options;
  options.smooth_surface = smooth;
  return compute_deviation(s.points, reference, options);
}

// Mean and std of the deviations against the noise's, both ways; returns the flat facets' mean offset.
double expect_noise(const Sample& s, const Mesh& reference, const char* what) {
  const DeviationStatistics noise = moments(s.offset_mm);
  const DeviationStatistics smooth = moments(deviation(s, reference, true).deviation_mm);
  const DeviationStatistics flat = moments(deviation(s, reference, false).deviation_mm);
  std::printf("%-28s noise mean %.5f std %.5f | smooth mean %.5f std %.5f | flat mean %.5f std %.5f mm\n", what,
              noise.mean_mm, noise.std_mm, smooth.mean_mm, smooth.std_mm, flat.mean_mm, flat.std_mm);
  EXPECT_NEAR(smooth.mean_mm, noise.mean_mm, 0.001) << what;
  EXPECT_NEAR(smooth.std_mm, noise.std_mm, 0.001) << what;
  return flat.mean_mm - noise.mean_mm;
}

// A closed tube of radius R meshed at `edge_mm` (the generator's staggered rows), sampled on the exact cylinder away
// from the open ends.
void check_tube(double radius_mm, double edge_mm, double min_flat_offset_mm) {
  TubeOptions t;
  t.radius_mm = radius_mm;
  t.length_mm = 200.0;
  t.edge_mm = edge_mm;
  const Mesh reference = generate_tube(t).mesh;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> azimuth(0.0, 2.0 * M_PI), z(-90.0, 90.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  Sample s;
  for (int i = 0; i < 5000; ++i) {
    const double a = azimuth(rng), e = noise(rng);
    s.points.emplace_back((radius_mm + e) * std::cos(a), (radius_mm + e) * std::sin(a), z(rng));
    s.offset_mm.push_back(e);
  }
  char what[64];
  std::snprintf(what, sizeof what, "tube R %g, edge %g mm", radius_mm, edge_mm);
  EXPECT_GT(expect_noise(s, reference, what), min_flat_offset_mm);
}

TEST(SmoothDeviation, TubeMeshesGiveTheNoise) {
  check_tube(150.0, 5.0, 0.004);  // chord error up to h^2 / (8 R) = 0.021 mm
  check_tube(20.0, 3.0, 0.01);    // a coarse mesh of a small tube: 0.056 mm
}

// The generated free-form surface (two waves and a dome), at 4 mm with its exact vertex normals and without them
// (angle-weighted from the faces), sampled on the exact surface away from its open border.
TEST(SmoothDeviation, FreeFormMeshGivesTheNoise) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> x(-85.0, 85.0), y(-60.0, 60.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  Sample s;
  for (int i = 0; i < 5000; ++i) {
    const double px = x(rng), py = y(rng), e = noise(rng);
    s.points.push_back(V(px, py, freeform_height(px, py)) + e * freeform_normal(px, py));
    s.offset_mm.push_back(e);
  }
  PartOptions part;
  part.edge_mm = 4.0;
  expect_noise(s, freeform_surface(part), "free-form, exact normals");
  part.vertex_normals = false;
  expect_noise(s, freeform_surface(part), "free-form, normals from faces");
}

// The stepped block (flat faces, 90 deg edges, a 45 deg chamfer, a boss): points around it measure the same to the
// smooth surface as to the flat facets, at faces, edges and corners alike.
TEST(SmoothDeviation, FlatPartsAndSharpEdgesDoNotChange) {
  PartOptions part;
  part.vertex_normals = false;
  const Mesh box = box_part(part);
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  Sample s;
  for (const V& v : box.vertices) s.points.push_back(v + V(u(rng), u(rng), u(rng)));
  const DeviationResult smooth = deviation(s, box, true), flat = deviation(s, box, false);
  double worst = 0.0;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    worst = std::max(worst, std::abs(smooth.deviation_mm[i] - flat.deviation_mm[i]));
  }
  std::printf("stepped block, %zu points: smooth and flat differ by at most %.3g mm\n", s.points.size(), worst);
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace conform
