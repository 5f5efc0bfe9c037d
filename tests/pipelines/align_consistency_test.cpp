// The bias measures of a fit against a cloud reference (pipelines/src/align/align_consistency.h): the reference
// fitted to the scan lands where the forward fit did when that fit is right, and it measures how far a forward pose
// is off when it is not; the fit against a wider-neighbourhood normal model stays put on a smooth surface and moves
// where the normals straddle a step; each difference enters the covariance as a bias.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "align/align_consistency.h"
#include "conform/core/geometry.h"
#include "conform/core/mesh.h"
#include "conform/core/normals.h"
#include "conform/core/random.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {
namespace {

// A smooth bumpy surface z = f(x, y) (three Gaussian bumps of different widths: every motion fixed), sampled at
// random with 0.02 mm of noise along z: the whole 100 x 100 mm as the reference, the middle 60 x 60 mm as the
// scan, both in one frame (the truth is the identity).
struct Pair {
  std::vector<Eigen::Vector3d> reference, scan;
};

double height(double x, double y) {
  return 6.0 * std::exp(-((x - 20) * (x - 20) + (y - 30) * (y - 30)) / 300.0) +
         4.0 * std::exp(-((x - 60) * (x - 60) + (y - 55) * (y - 55)) / 150.0) -
         5.0 * std::exp(-((x - 45) * (x - 45) + (y - 75) * (y - 75)) / 400.0);
}

std::vector<Eigen::Vector3d> samples(double from, double to, std::size_t count, std::uint64_t seed) {
  Random random(seed);
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < count; ++i) {
    const double x = random.uniform(from, to), y = random.uniform(from, to);
    points.emplace_back(x, y, height(x, y) + 0.02 * random.normal());
  }
  return points;
}

Pair bumpy_pair() { return {samples(0.0, 100.0, 12000, 3), samples(20.0, 80.0, 6000, 4)}; }

IcpOptions options() {
  IcpOptions o;
  o.max_correspondence_distance_mm = 10.0;
  o.estimate_overlap = true;
  return o;
}

IcpReference cloud_of(const std::vector<Eigen::Vector3d>& points) {
  Mesh cloud;
  cloud.vertices = points;
  return IcpReference(cloud);
}

IcpResult forward_fit(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference) {
  return icp(scan, reference, Eigen::Isometry3d::Identity(), options());
}

TEST(InverseConsistency, RightFitIsConsistent) {
  const Pair pair = bumpy_pair();
  const IcpReference reference = cloud_of(pair.reference);
  const IcpResult forward = forward_fit(pair.scan, reference);
  ASSERT_TRUE(forward.converged);
  const FitDiscrepancy c = inverse_consistency(pair.scan, reference, forward, options());
  ASSERT_TRUE(c.ran);
  // Two noise-free samplings of one surface: both fits within the sampling's own effect of the truth.
  EXPECT_LT(c.largest_displacement_mm, 0.02);  // measured 0.010
  EXPECT_LT(c.twist.head<3>().norm(), 3e-4);   // rad (measured 1.4e-4)
  EXPECT_LT(c.twist.tail<3>().norm(), 0.02);   // mm
}

// A forward pose 0.5 mm and 0.2 deg off the truth (as a biased fit would stop): the reverse fit, started from it,
// finds the truth, so the consistency measures the offset.
TEST(InverseConsistency, MeasuresAnOffsetForwardPose) {
  const Pair pair = bumpy_pair();
  const IcpReference reference = cloud_of(pair.reference);
  IcpResult forward = forward_fit(pair.scan, reference);
  ASSERT_TRUE(forward.converged);
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
  offset.linear() = Eigen::AngleAxisd(0.2 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  offset.translation() = Eigen::Vector3d(0.3, -0.4, 0.0);
  forward.T_ref_scan = offset;
  const FitDiscrepancy c = inverse_consistency(pair.scan, reference, forward, options());
  ASSERT_TRUE(c.ran);
  EXPECT_NEAR(c.twist(2), 0.2 * M_PI / 180.0, 3e-4);  // measured 1.5e-4 off
  const Eigen::Vector3d& centre = forward.degeneracy.centre;
  const Eigen::Vector3d moved = offset * centre - centre;
  EXPECT_NEAR((c.twist.tail<3>() - moved).norm(), 0.0, 0.02);
  double largest = 0.0;
  for (const Eigen::Vector3d& p : pair.scan) largest = std::max(largest, (offset * p - p).norm());
  EXPECT_NEAR(c.largest_displacement_mm, largest, 0.02);
}

TEST(InverseConsistency, BiasAddsToTheCovariance) {
  FitDiscrepancy c;
  c.ran = true;
  c.twist << 0.001, 0.0, 0.0, 0.0, 0.3, 0.4;
  DegeneracyReport d;
  d.covariance = Matrix6d::Identity() * 0.01;
  add_bias(c, d);
  EXPECT_NEAR(d.std(0), std::sqrt(0.01 + 1e-6), 1e-12);
  EXPECT_NEAR(d.std(3), 0.1, 1e-12);
  EXPECT_NEAR(d.std(4), std::sqrt(0.01 + 0.09), 1e-12);
  EXPECT_NEAR(d.covariance(4, 5), 0.12, 1e-12);
  c.ran = false;  // a reverse fit that did not converge adds nothing
  const Matrix6d before = d.covariance;
  add_bias(c, d);
  EXPECT_EQ(d.covariance, before);
}

// On the smooth bumpy surface the normals over 16 and over 64 neighbours describe one surface: the fit stays.
TEST(NormalModelSpread, SmoothSurfaceStays) {
  const Pair pair = bumpy_pair();
  const IcpReference reference = cloud_of(pair.reference);
  const IcpResult forward = forward_fit(pair.scan, reference);
  ASSERT_TRUE(forward.converged);
  const FitDiscrepancy c = normal_model_spread(pair.scan, reference, forward, options());
  ASSERT_TRUE(c.ran);
  std::printf("  normal-model spread on the smooth surface %.4f mm\n", c.largest_displacement_mm);
  EXPECT_LT(c.largest_displacement_mm, 0.02);
}

// A staircase of 1 mm steps (every 6 mm along x, the treads 0.5 mm apart along x as the sparse reference's rows)
// with a tilted plane beside it: its step risers are sampled by no point, so the normals over 64 neighbours tilt
// across the treads' edges where those over 16 do not, and the point-to-plane minimum along x moves with them. The
// spread measures that move: it is the pose the same fit reaches against the wider model, within a few
// micrometres, and it is not nothing.
TEST(NormalModelSpread, MeasuresTheMoveOfTheMinimumWithTheModel) {
  Random random(7);
  std::vector<Eigen::Vector3d> reference, scan;
  const auto surface = [](double x, double y) { return std::floor(x / 6.0) * 1.0 + 0.05 * y; };
  for (double x = 0.0; x < 60.0; x += 0.5) {
    for (double y = 0.0; y < 30.0; y += 0.5) reference.emplace_back(x, y, surface(x, y) + 0.02 * random.normal());
  }
  for (int i = 0; i < 5000; ++i) {
    const double x = random.uniform(10.0, 50.0), y = random.uniform(5.0, 25.0);
    scan.emplace_back(x, y, surface(x, y) + 0.02 * random.normal());
  }
  const IcpReference model = cloud_of(reference);
  const IcpResult forward = forward_fit(scan, model);
  ASSERT_TRUE(forward.converged);
  const FitDiscrepancy c = normal_model_spread(scan, model, forward, options());
  ASSERT_TRUE(c.ran);
  // The same fit against the 64-neighbour model, by hand.
  NormalOptions wide;
  wide.k = 64;
  wide.viewpoint = centroid(reference);
  const pcl::PointCloud<pcl::Normal> normals = estimate_normals(model.tree(), wide);
  Mesh with_normals;
  with_normals.vertices = reference;
  for (const pcl::Normal& n : normals) with_normals.normals.push_back(n.getNormalVector3fMap().cast<double>());
  const IcpResult other = icp(scan, IcpReference(with_normals), forward.T_ref_scan, options());
  double largest = 0.0;
  for (const Eigen::Vector3d& p : scan)
    largest = std::max(largest, (forward.T_ref_scan * p - other.T_ref_scan * p).norm());
  EXPECT_NEAR(c.largest_displacement_mm, largest, 1e-9);
  std::printf("  normal-model spread on the staircase %.4f mm\n", c.largest_displacement_mm);
  EXPECT_GT(c.largest_displacement_mm, 0.004);  // measured 0.0086
}

}  // namespace
}  // namespace conform::detail
