// What the cylinder fit does with data that do not define a cylinder: a plane and a sphere come back as failures
// with their reason; degenerate input (too few points, coincident points, a line, NaN, bad options) throws an Error
// that says what is wrong; radius bounds and an axis prior that exclude the truth are reported, not obeyed silently.

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/fitting/cylinder.h"
#include "tube_fit.h"

namespace conform {
namespace {

using test::kDeg;

// A deterministic normal draw (Box-Muller on a 64-bit LCG): the test's own noise, independent of the library.
class Noise {
 public:
  explicit Noise(std::uint64_t seed) : state_(seed) {}
  double uniform() {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    return (static_cast<double>(state_ >> 11) + 0.5) / 9007199254740992.0;
  }
  double normal() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(2.0 * kPi * uniform()); }

 private:
  std::uint64_t state_;
};

Cloud make_cloud(const std::vector<Eigen::Vector3d>& points) {
  Cloud cloud;
  for (const auto& p : points) {
    cloud.points.push_back(
        pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  }
  return cloud;
}

// A 300 x 200 mm plate, tilted, with Gaussian noise along its normal (5000 points: the sanitizer build is slow).
Cloud noisy_plane(double sigma, std::uint64_t seed) {
  Noise noise(seed);
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  const Eigen::Vector3d u = n.unitOrthogonal();
  const Eigen::Vector3d v = n.cross(u);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 5000; ++i) {
    points.push_back(Eigen::Vector3d(40.0, 50.0, 60.0) + 300.0 * (noise.uniform() - 0.5) * u +
                     200.0 * (noise.uniform() - 0.5) * v + sigma * noise.normal() * n);
  }
  return make_cloud(points);
}

// 5000 points uniform on a sphere of radius 100 mm with radial Gaussian noise.
Cloud noisy_sphere(double sigma, std::uint64_t seed) {
  Noise noise(seed);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 5000; ++i) {
    const double z = 2.0 * noise.uniform() - 1.0;
    const double phi = 2.0 * kPi * noise.uniform();
    const double s = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d d(s * std::cos(phi), s * std::sin(phi), z);
    points.push_back(Eigen::Vector3d(-30.0, 10.0, 200.0) + (100.0 + sigma * noise.normal()) * d);
  }
  return make_cloud(points);
}

TEST(CylinderFailure, ANoisyPlaneIsReportedAsAPlane) {
  const CylinderFitResult fit = fit_cylinder(noisy_plane(0.2, 3), CylinderFitOptions{});
  std::printf("[figures] plane: %s\n", fit.termination.c_str());
  EXPECT_FALSE(fit.ok);
  EXPECT_EQ(fit.failure, CylinderFailure::kPlane) << fit.termination;
  EXPECT_NE(fit.termination.find("not a cylinder"), std::string::npos);
  EXPECT_NE(fit.termination.find("plane"), std::string::npos);
}

TEST(CylinderFailure, AnExactPlaneIsReportedAsAPlane) {
  const CylinderFitResult fit = fit_cylinder(noisy_plane(0.0, 4), CylinderFitOptions{});
  EXPECT_FALSE(fit.ok);
  EXPECT_EQ(fit.failure, CylinderFailure::kPlane) << fit.termination;
}

TEST(CylinderFailure, ASphereIsReportedAsASphere) {
  const CylinderFitResult fit = fit_cylinder(noisy_sphere(0.1, 5), CylinderFitOptions{});
  std::printf("[figures] sphere: %s\n", fit.termination.c_str());
  EXPECT_FALSE(fit.ok);
  EXPECT_EQ(fit.failure, CylinderFailure::kSphere) << fit.termination;
  EXPECT_NE(fit.termination.find("sphere"), std::string::npos);
}

std::string error_of(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                     const CylinderFitOptions& options = {}) {
  try {
    fit_cylinder(points, normals, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(CylinderFailure, DegenerateInputThrowsAClearError) {
  const std::vector<Eigen::Vector3d> five(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_NE(error_of(five, five).find("needs at least 6"), std::string::npos) << error_of(five, five);

  const std::vector<Eigen::Vector3d> same(50, Eigen::Vector3d(1, 2, 3));
  const std::vector<Eigen::Vector3d> up(50, Eigen::Vector3d::UnitZ());
  EXPECT_NE(error_of(same, up).find("coincide"), std::string::npos) << error_of(same, up);

  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 50; ++i) line.push_back(Eigen::Vector3d(1, 2, 3) + i * Eigen::Vector3d(0.5, -1.0, 2.0));
  EXPECT_NE(error_of(line, up).find("on a line"), std::string::npos) << error_of(line, up);

  std::vector<Eigen::Vector3d> with_nan = line;
  with_nan[7].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_of(with_nan, up).find("point 7 is not finite"), std::string::npos) << error_of(with_nan, up);

  std::vector<Eigen::Vector3d> zero_normal = up;
  zero_normal[9].setZero();
  EXPECT_NE(error_of(line, zero_normal).find("normal 9"), std::string::npos);
  EXPECT_NE(error_of(line, std::vector<Eigen::Vector3d>(49, Eigen::Vector3d::UnitZ())).find("49 normals"),
            std::string::npos);

  CylinderFitOptions bad;
  bad.max_radius_mm = -1.0;
  EXPECT_NE(error_of(line, up, bad).find("max_radius_mm"), std::string::npos) << error_of(line, up, bad);
}

TEST(CylinderFailure, RadiusBoundsThatExcludeTheTubeAreReported) {
  TubeOptions tube = test::tube_scan_options(120.0, 0.1, 21);
  tube.vertex_count = 20000;
  const TubeScan scan = generate_tube(tube);
  const std::vector<Eigen::Vector3d> normals = estimate_normals(scan.mesh, 16);
  CylinderFitOptions options;
  options.min_radius_mm = 160.0;  // the tube's radius is 150 mm
  const CylinderFitResult fit = fit_cylinder(scan.mesh.vertices, normals, options);
  EXPECT_FALSE(fit.ok);
  EXPECT_EQ(fit.failure, CylinderFailure::kRadiusAtBound) << fit.termination;
  EXPECT_GE(fit.cylinder.radius_mm, 160.0 - 1e-9);

  options.min_radius_mm = 140.0;
  options.max_radius_mm = 155.0;
  const CylinderFitResult inside = fit_cylinder(scan.mesh.vertices, normals, options);
  ASSERT_TRUE(inside.ok) << inside.termination;
  EXPECT_NEAR(inside.cylinder.radius_mm, 150.0, 0.02);
}

TEST(CylinderFailure, AnAxisPriorSteersAndRejects) {
  TubeOptions tube = test::tube_scan_options(120.0, 0.1, 22);
  tube.vertex_count = 20000;
  const TubeScan scan = generate_tube(tube);
  const std::vector<Eigen::Vector3d> normals = estimate_normals(scan.mesh, 16);
  CylinderFitOptions options;
  options.axis_prior = -3.0 * scan.truth.axis_direction;  // any length, either sign
  const CylinderFitResult fit = fit_cylinder(scan.mesh.vertices, normals, options);
  ASSERT_TRUE(fit.ok) << fit.termination;
  EXPECT_GT(fit.cylinder.axis_direction.dot(options.axis_prior), 0.0);  // oriented along the prior

  // A prior 45 deg off the tube's axis: no hypothesis within its 10 deg cone fits.
  const Eigen::AngleAxisd tilt(45.0 * kDeg, scan.truth.axis_direction.unitOrthogonal());
  options.axis_prior = tilt * scan.truth.axis_direction;
  const CylinderFitResult off = fit_cylinder(scan.mesh.vertices, normals, options);
  EXPECT_FALSE(off.ok);
  EXPECT_TRUE(off.failure == CylinderFailure::kAxisOutsidePrior || off.failure == CylinderFailure::kNoConsensus)
      << to_string(off.failure) << ": " << off.termination;
}

}  // namespace
}  // namespace conform
