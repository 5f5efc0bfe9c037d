// Properties of the cylinder fit beyond the headline figures: the inner wall, the covariance of a partial arc against
// the Cramer-Rao bound and against the scatter over seeds, byte-identical results for the same seed, and the cloud
// entry point that estimates its own normals.

#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "conform/fitting/cylinder.h"
#include "tube_fit.h"

namespace conform {
namespace {

using test::kDeg;

TEST(CylinderProperties, InnerWallOfA60DegPatch) {
  TubeOptions tube = test::tube_scan_options(60.0, 0.1, 31);
  tube.surface = TubeSurface::kInner;
  tube.vertex_count = 20000;
  const test::FittedScan f = test::fit_generated(tube);
  test::print_figures("inner wall, 60 deg patch, sigma 0.1", f);
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  EXPECT_EQ(f.fit.side, CylinderSide::kInner);
  EXPECT_NEAR(f.fit.arc_rad, 60.0 * kDeg, 1.0 * kDeg);
  EXPECT_LE(std::abs(f.error.radius_mm), 4.0 * f.fit.radius_std_mm);
  EXPECT_LE(f.error.angle_deg, 0.005);
}

// For n points spread evenly over an arc of half-angle h with noise sigma along the normal, the radius variance of a
// circle fit is sigma^2 / n * E[cos^2] / (E[cos^2] - E[cos]^2) (the radius and the centre's shift towards the arc are
// nearly the same regressor); the axis terms are uncorrelated with both. This is what the covariance must give.
double predicted_radius_std(double sigma, double n, double half_angle) {
  const double mean_cos = std::sin(half_angle) / half_angle;
  const double mean_cos2 = 0.5 + std::sin(2.0 * half_angle) / (4.0 * half_angle);
  return sigma / std::sqrt(n) * std::sqrt(mean_cos2 / (mean_cos2 - mean_cos * mean_cos));
}

TEST(CylinderProperties, CovarianceOfA60DegPatchMatchesTheoryAndScatter) {
  double sum_squares = 0.0;
  double sum_std = 0.0;
  constexpr int kSeeds = 6;
  for (int seed = 0; seed < kSeeds; ++seed) {
    TubeOptions tube = test::tube_scan_options(60.0, 0.2, 100 + static_cast<std::uint64_t>(seed));
    tube.vertex_count = 5000;
    const test::FittedScan f = test::fit_generated(tube);
    ASSERT_TRUE(f.fit.ok) << f.fit.termination;
    const double predicted = predicted_radius_std(0.2, static_cast<double>(f.fit.inliers.size()), 30.0 * kDeg);
    EXPECT_NEAR(f.fit.radius_std_mm, predicted, 0.1 * predicted);
    sum_squares += f.error.radius_mm * f.error.radius_mm;
    sum_std += f.fit.radius_std_mm;
  }
  const double rms_error = std::sqrt(sum_squares / kSeeds);
  const double mean_std = sum_std / kSeeds;
  std::printf(
      "[figures] 60 deg patch, 5k points, sigma 0.2: radius std %.4f mm (covariance), rms error %.4f mm over "
      "%d seeds\n",
      mean_std, rms_error, kSeeds);
  // With 6 draws the RMS of a normal error lies within [0.45, 1.6] sigma 95% of the time.
  EXPECT_GT(rms_error, 0.3 * mean_std);
  EXPECT_LT(rms_error, 2.0 * mean_std);
}

TEST(CylinderProperties, SameSeedSameBytes) {
  TubeOptions tube = test::tube_scan_options(90.0, 0.5, 41);
  tube.vertex_count = 10000;
  const TubeScan scan = generate_tube(tube);
  const std::vector<Eigen::Vector3d> normals = estimate_normals(scan.mesh, 16);
  CylinderFitOptions options;
  options.seed = 7;
  const CylinderFitResult a = fit_cylinder(scan.mesh.vertices, normals, options);
  const CylinderFitResult b = fit_cylinder(scan.mesh.vertices, normals, options);
  ASSERT_TRUE(a.ok) << a.termination;
  EXPECT_EQ(std::memcmp(&a.cylinder, &b.cylinder, sizeof(Cylinder)), 0);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.radius_std_mm, b.radius_std_mm);

  options.seed = 8;  // another RANSAC draw, the same answer to within its uncertainty
  const CylinderFitResult c = fit_cylinder(scan.mesh.vertices, normals, options);
  ASSERT_TRUE(c.ok) << c.termination;
  EXPECT_NEAR(c.cylinder.radius_mm, a.cylinder.radius_mm, 0.05 * a.radius_std_mm);
}

TEST(CylinderProperties, CloudWithoutNormalsGetsPcaNormals) {
  TubeOptions tube = test::tube_scan_options(90.0, 0.2, 51);
  tube.vertex_count = 20000;
  const TubeScan scan = generate_tube(tube);
  const Cloud cloud = to_cloud(scan.mesh);
  ASSERT_FALSE(cloud.has_normals());
  const CylinderFitResult fit = fit_cylinder(cloud, CylinderFitOptions{});
  ASSERT_TRUE(fit.ok) << fit.termination;
  EXPECT_LE(std::abs(fit.cylinder.radius_mm - 150.0), 4.0 * fit.radius_std_mm + 1e-4);  // + float storage
}

TEST(CylinderProperties, AGivenThresholdIsUsed) {
  TubeOptions tube = test::tube_scan_options(360.0, 0.2, 61);
  tube.vertex_count = 20000;
  tube.outlier_fraction = 0.1;
  tube.outlier_distance_mm = 2.0;  // outliers 2 to 4 mm off the wall
  CylinderFitOptions options;
  options.threshold_mm = 1.5;
  const test::FittedScan f = test::fit_generated(tube, options);
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  EXPECT_EQ(f.fit.threshold_mm, 1.5);
  EXPECT_NEAR(f.fit.inlier_fraction, 0.9, 0.005);
  EXPECT_LE(std::abs(f.error.radius_mm), 4.0 * f.fit.radius_std_mm);
}

}  // namespace
}  // namespace conform
