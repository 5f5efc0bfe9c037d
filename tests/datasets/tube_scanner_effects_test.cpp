// generate_tube's scanner effects (noise, holes, outliers), its determinism and its refusals.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/datasets/tube.h"

namespace conform {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Signed distance of each vertex from its exact position along the exact normal (tube frame radial for a round
// tube), and the full 3D offsets.
std::vector<double> normal_residuals(const TubeScan& scan, const TubeOptions& options) {
  std::vector<double> out;
  for (std::size_t i = 0; i < scan.mesh.vertices.size(); ++i) {
    const Eigen::Vector2d& p = scan.truth.vertex_parameters[i];
    const Eigen::Vector3d n = tube_surface(options, p.x(), p.y()).normal;
    out.push_back((scan.mesh.vertices[i] - scan.truth.exact_vertices[i]).dot(n));
  }
  return out;
}

std::pair<double, double> mean_and_std(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / static_cast<double>(values.size());
  double sq = 0.0;
  for (double v : values) sq += (v - mean) * (v - mean);
  return {mean, std::sqrt(sq / static_cast<double>(values.size() - 1))};
}

TubeOptions noisy_tube() {
  TubeOptions options;
  options.radius_mm = 150.0;
  options.length_mm = 300.0;
  options.edge_mm = 3.0;  // about 34,000 vertices
  options.T_world_tube = tube_frame({10.0, 20.0, 30.0}, {0.0, 1.0, 1.0}, {1.0, 0.0, 0.0});
  return options;
}

TEST(TubeNoise, GaussianAlongTheNormalHasTheGivenStandardDeviation) {
  TubeOptions options = noisy_tube();
  options.noise_mm = 0.1;
  const TubeScan scan = generate_tube(options);
  const std::vector<double> r = normal_residuals(scan, options);
  const auto [mean, sd] = mean_and_std(r);
  const double n = static_cast<double>(r.size());
  std::printf("[ measured ] gaussian sigma 0.1: mean %.5f std %.5f mm over %zu vertices\n", mean, sd, r.size());
  // The sample std's relative standard error is 1 / sqrt(2N) = 0.4%: 2% is five of them.
  EXPECT_NEAR(sd, 0.1, 0.002);
  EXPECT_NEAR(mean, 0.0, 4.0 * 0.1 / std::sqrt(n));
  // Along the normal only: nothing left over sideways.
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_NEAR((scan.mesh.vertices[i] - scan.truth.exact_vertices[i]).norm(), std::abs(r[i]), 1e-12);
  }
}

TEST(TubeNoise, UniformAlongTheNormalStaysWithinItsHalfWidth) {
  TubeOptions options = noisy_tube();
  options.noise_mm = 0.1;
  options.noise_distribution = NoiseDistribution::kUniform;
  const TubeScan scan = generate_tube(options);
  const std::vector<double> r = normal_residuals(scan, options);
  const auto [mean, sd] = mean_and_std(r);
  const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
  std::printf("[ measured ] uniform +-0.1: std %.5f mm (0.1/sqrt 3 = %.5f), range [%.5f, %.5f]\n", sd,
              0.1 / std::sqrt(3.0), *lo, *hi);
  EXPECT_NEAR(sd, 0.1 / std::sqrt(3.0), 0.02 * 0.1 / std::sqrt(3.0));
  EXPECT_GE(*lo, -0.1);
  EXPECT_LE(*hi, 0.1);
  EXPECT_LT(*lo, -0.099);  // the range is used up to its ends
  EXPECT_GT(*hi, 0.099);
  EXPECT_NEAR(mean, 0.0, 4.0 * sd / std::sqrt(static_cast<double>(r.size())));
}

TEST(TubeNoise, IsotropicNoiseHasTheSameSpreadOnEveryAxis) {
  TubeOptions options = noisy_tube();
  options.noise_mm = 0.05;
  options.noise_direction = NoiseDirection::kIsotropic;
  for (NoiseDistribution distribution : {NoiseDistribution::kGaussian, NoiseDistribution::kUniform}) {
    options.noise_distribution = distribution;
    const TubeScan scan = generate_tube(options);
    // Uniform in a ball of radius a: each coordinate has variance a^2 / 5.
    const double expected = distribution == NoiseDistribution::kGaussian ? 0.05 : 0.05 / std::sqrt(5.0);
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<double> d;
      for (std::size_t i = 0; i < scan.mesh.vertices.size(); ++i) {
        d.push_back(scan.mesh.vertices[i][axis] - scan.truth.exact_vertices[i][axis]);
        if (distribution == NoiseDistribution::kUniform) {
          ASSERT_LE((scan.mesh.vertices[i] - scan.truth.exact_vertices[i]).norm(), 0.05);
        }
      }
      EXPECT_NEAR(mean_and_std(d).second, expected, 0.02 * expected) << "axis " << axis;
    }
  }
}

// Area of the faces, in the tube's own (noise-free) geometry.
double area_of(const TubeScan& scan) { return surface_area(scan.mesh); }

TEST(TubeHoles, GivenHolesRemoveTheirAreaAndLeaveNoUnusedVertex) {
  TubeOptions options = noisy_tube();
  options.edge_mm = 2.0;
  const double full = area_of(generate_tube(options));
  options.holes = {
      {0.0, 0.0, 20.0}, {120.0 * kDeg, 80.0, 25.0}, {179.0 * kDeg, -100.0, 15.0}};  // the last crosses +-180
  const TubeScan scan = generate_tube(options);
  const double expected = M_PI * (20.0 * 20.0 + 25.0 * 25.0 + 15.0 * 15.0);
  const double removed = full - area_of(scan);
  std::printf("[ measured ] given holes removed %.1f mm2 of %.1f (%.2f%%)\n", removed, expected,
              100.0 * (removed - expected) / expected);
  EXPECT_NEAR(removed, expected, 0.03 * expected);
  std::vector<bool> used(scan.mesh.vertices.size(), false);
  for (const Face& f : scan.mesh.faces) {
    for (std::int32_t v : f) used[static_cast<std::size_t>(v)] = true;
  }
  EXPECT_TRUE(std::all_of(used.begin(), used.end(), [](bool u) { return u; }));
  EXPECT_EQ(scan.truth.vertex_parameters.size(), scan.mesh.vertices.size());
  EXPECT_EQ(scan.truth.holes.size(), 3u);
}

TEST(TubeHoles, RandomHolesFitOnAPatchWithoutOverlap) {
  TubeOptions options = noisy_tube();
  options.edge_mm = 2.0;
  options.arc_rad = 90.0 * kDeg;
  const double full = area_of(generate_tube(options));
  options.random_holes = 4;
  options.random_hole_radius_mm = 15.0;
  options.seed = 11;
  const TubeScan scan = generate_tube(options);
  ASSERT_EQ(scan.truth.holes.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const TubeHole& a = scan.truth.holes[i];
    EXPECT_GE(150.0 * (a.azimuth_rad + 45.0 * kDeg), 15.0 - 1e-9);  // inside the patch's borders
    EXPECT_GE(150.0 * (45.0 * kDeg - a.azimuth_rad), 15.0 - 1e-9);
    EXPECT_LE(std::abs(a.z_mm), 150.0 - 15.0);
    for (std::size_t j = 0; j < i; ++j) {
      const TubeHole& b = scan.truth.holes[j];
      EXPECT_GE(std::hypot(150.0 * (a.azimuth_rad - b.azimuth_rad), a.z_mm - b.z_mm), 30.0);
    }
  }
  const double expected = 4.0 * M_PI * 15.0 * 15.0;
  const double removed = full - area_of(scan);
  std::printf("[ measured ] random holes removed %.1f mm2 of %.1f\n", removed, expected);
  EXPECT_NEAR(removed, expected, 0.03 * expected);

  options.random_holes = 200;  // cannot fit
  EXPECT_THROW(generate_tube(options), Error);
}

TEST(TubeOutliers, AShareOfVerticesMovesFarAlongTheNormal) {
  TubeOptions options = noisy_tube();
  options.outlier_fraction = 0.01;
  options.outlier_distance_mm = 4.0;
  const TubeScan scan = generate_tube(options);
  const std::size_t n = scan.mesh.vertices.size();
  const auto& outliers = scan.truth.outlier_indices;
  EXPECT_EQ(outliers.size(), static_cast<std::size_t>(std::llround(0.01 * static_cast<double>(n))));
  EXPECT_TRUE(std::is_sorted(outliers.begin(), outliers.end()));
  EXPECT_EQ(std::adjacent_find(outliers.begin(), outliers.end()), outliers.end());
  const std::vector<double> r = normal_residuals(scan, options);
  int inward = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const bool outlier = std::binary_search(outliers.begin(), outliers.end(), static_cast<std::int32_t>(i));
    if (!outlier) {
      ASSERT_EQ(scan.mesh.vertices[i], scan.truth.exact_vertices[i]);
      continue;
    }
    EXPECT_GE(std::abs(r[i]), 4.0 - 1e-9);
    EXPECT_LE(std::abs(r[i]), 8.0 + 1e-9);
    inward += r[i] < 0.0 ? 1 : 0;
  }
  EXPECT_GT(inward, 0);  // both sides occur
  EXPECT_LT(inward, static_cast<int>(outliers.size()));
}

TEST(TubeDeterminism, SameSeedSameMeshDifferentSeedDifferentMesh) {
  TubeOptions options = noisy_tube();
  options.noise_mm = 0.05;
  options.random_holes = 3;
  options.outlier_fraction = 0.002;
  options.seed = 42;
  const TubeScan a = generate_tube(options);
  const TubeScan b = generate_tube(options);
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);  // bitwise equal doubles
  EXPECT_EQ(a.mesh.faces, b.mesh.faces);
  EXPECT_EQ(a.truth.outlier_indices, b.truth.outlier_indices);
  options.seed = 43;
  const TubeScan c = generate_tube(options);
  EXPECT_NE(a.mesh.vertices, c.mesh.vertices);
  EXPECT_NE(a.truth.outlier_indices, c.truth.outlier_indices);
}

TEST(TubeDeterminism, AnEffectDrawsFromItsOwnStream) {
  TubeOptions options = noisy_tube();
  options.noise_mm = 0.05;
  const TubeScan plain = generate_tube(options);
  options.outlier_fraction = 0.01;
  const TubeScan with_outliers = generate_tube(options);
  std::size_t same = 0;
  for (std::size_t i = 0; i < plain.mesh.vertices.size(); ++i) {
    same += plain.mesh.vertices[i] == with_outliers.mesh.vertices[i] ? 1 : 0;
  }
  EXPECT_EQ(same, plain.mesh.vertices.size() - with_outliers.truth.outlier_indices.size());
}

TEST(TubeOptions, VertexCountChoosesTheEdgeLength) {
  TubeOptions options;
  options.radius_mm = 1000.0;
  options.length_mm = 800.0;
  options.arc_rad = 60.0 * kDeg;
  options.vertex_count = 50000;
  const TubeScan scan = generate_tube(options);
  std::printf("[ measured ] 60-degree patch asked for 50000 vertices: %zu, edge %.3f mm\n", scan.mesh.vertices.size(),
              scan.truth.grid.edge_mm);
  EXPECT_NEAR(static_cast<double>(scan.mesh.vertices.size()), 50000.0, 0.02 * 50000.0);
}

TEST(TubeOptions, InvalidValuesAreRejectedWithAMessageNamingThem) {
  const std::vector<std::pair<std::string, void (*)(TubeOptions&)>> cases = {
      {"radius", [](TubeOptions& o) { o.radius_mm = 0.0; }},
      {"length", [](TubeOptions& o) { o.length_mm = -5.0; }},
      {"arc", [](TubeOptions& o) { o.arc_rad = 7.0; }},
      {"edge", [](TubeOptions& o) { o.edge_mm = 0.0; }},
      {"triangles", [](TubeOptions& o) { o.edge_mm = 1e-3; }},
      {"rigid", [](TubeOptions& o) { o.T_world_tube.linear() *= 2.0; }},
      {"radius", [](TubeOptions& o) { o.ovality_mm = 200.0; }},
      {"seam width", [](TubeOptions& o) { o.seam_height_mm = 1.0, o.seam_width_mm = 0.0; }},
      {"bump 1",
       [](TubeOptions& o) {
         o.bumps = {{0.0, 0.0, 1.0, -2.0}};
       }},
      {"noise", [](TubeOptions& o) { o.noise_mm = -0.1; }},
      {"noise", [](TubeOptions& o) { o.noise_mm = std::nan(""); }},
      {"hole 1",
       [](TubeOptions& o) {
         o.holes = {{0.0, 0.0, 0.0}};
       }},
      {"outlier fraction", [](TubeOptions& o) { o.outlier_fraction = 1.0; }},
      {"vertex count", [](TubeOptions& o) { o.vertex_count = -3; }},
  };
  for (const auto& [word, mutate] : cases) {
    TubeOptions options;
    std::string error;
    ASSERT_TRUE(options.IsValid(&error)) << error;
    mutate(options);
    EXPECT_FALSE(options.IsValid(&error)) << word;
    EXPECT_NE(error.find(word), std::string::npos) << "'" << error << "' should name " << word;
    EXPECT_THROW(generate_tube(options), Error) << word;
  }
}

TEST(TubeOptions, FrameFollowsTheAxisAndTheAzimuthReference) {
  const Eigen::Isometry3d T = tube_frame({1.0, 2.0, 3.0}, {0.0, 0.0, -2.0}, {1.0, 1.0, 5.0});
  EXPECT_LT((T.linear().col(2) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-15);
  EXPECT_LT((T.linear().col(0) - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 1e-15);
  EXPECT_NEAR(T.linear().determinant(), 1.0, 1e-15);
  EXPECT_EQ(T.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(tube_frame({0, 0, 0}, {0, 0, 1}, {0, 0, 3}), Error);
  EXPECT_THROW(tube_frame({0, 0, 0}, {0, 0, 0}, {1, 0, 0}), Error);
  EXPECT_EQ(default_azimuth_reference({0, 0, 1}), Eigen::Vector3d::UnitX());
  EXPECT_EQ(default_azimuth_reference({1, 0, 0}), Eigen::Vector3d::UnitY());
}

}  // namespace
}  // namespace conform
