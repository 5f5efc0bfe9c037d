// Constraint from uncertainty (registration/degeneracy.h, analyze_constraint): the pose covariance sigma^2 (N H)^-1
// against its closed form on a plane, and ICP on the ribbed plate (datasets/ribbed_plate.h), whose translation along
// the ribs is weak but measured: it must be fitted, not held, and its reported std must cover its error.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "conform/core/cloud.h"
#include "conform/core/error.h"
#include "conform/core/random.h"
#include "conform/datasets/ribbed_plate.h"
#include "conform/datasets/tube.h"
#include "conform/registration/degeneracy.h"
#include "conform/registration/icp.h"
#include "conform/registration/surface_noise.h"
#include "registration_test_util.h"

namespace conform {
namespace {

using test::kDeg;

Cloud to_cloud(const std::vector<Eigen::Vector3d>& points) {
  Cloud cloud;
  for (const Eigen::Vector3d& p : points) {
    cloud.points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  return cloud;
}

// A plane z = 10 sampled on a 21 x 11 grid about (7, -4), normals +z; sxx, syy: the sums of the squared offsets
// from the centre along x and y.
struct PlaneGrid {
  std::vector<Eigen::Vector3d> q, n;
  double sxx = 0.0, syy = 0.0;
};

PlaneGrid plane_grid() {
  PlaneGrid g;
  for (int i = -10; i <= 10; ++i) {
    for (int j = -5; j <= 5; ++j) {
      g.q.emplace_back(3.0 * i + 7.0, 2.0 * j - 4.0, 10.0);
      g.n.emplace_back(0.0, 0.0, 1.0);
      g.sxx += 9.0 * i * i;
      g.syy += 4.0 * j * j;
    }
  }
  return g;
}

// The grid above: var(tz) = sigma^2 / N, var(rx) = sigma^2 / sum (y - y_c)^2,
// var(ry) = sigma^2 / sum (x - x_c)^2 (the residual's derivatives are 1, y - y_c and -(x - x_c)); the in-plane motions
// are unconstrained and held.
TEST(Constraint, PlaneCovarianceIsTheClosedForm) {
  const PlaneGrid grid = plane_grid();
  const std::vector<Eigen::Vector3d>&q = grid.q, &n = grid.n;
  const double sxx = grid.sxx, syy = grid.syy;
  const double sigma = 0.005, count = static_cast<double>(q.size());
  const DegeneracyReport r = analyze_constraint(plane_normal_matrix(q, n), sigma, 0.02, 0.01 * kDeg);
  EXPECT_NEAR(r.std(5), sigma / std::sqrt(count), 1e-12);
  EXPECT_NEAR(r.std(0), sigma / std::sqrt(syy), 1e-12);
  EXPECT_NEAR(r.std(1), sigma / std::sqrt(sxx), 1e-12);
  EXPECT_NEAR(r.covariance(5, 5), sigma * sigma / count, 1e-15);
  EXPECT_GT(r.std(3), 1e3);  // in-plane: no constraint at all
  ASSERT_EQ(r.directions.size(), 3u);
  int held = 0;
  for (const ConstraintDirection& d : r.eigen_directions) held += d.held ? 1 : 0;
  EXPECT_EQ(held, 3);
  // A tolerance below rx's and ry's std does not hold them: they are measured within ten times the best direction's
  // std (relative eigenvalue >= 1e-2), and holding them at the start cannot beat the data.
  const DegeneracyReport tight = analyze_constraint(plane_normal_matrix(q, n), sigma, 1.0, 0.1 * r.std(0));
  EXPECT_EQ(tight.directions.size(), 3u);
  // A weak direction (relative eigenvalue below 1e-2) is held when its std exceeds the tolerance, fitted when not.
  std::vector<Eigen::Vector3d> q2 = q, n2 = n;
  for (int k : {-1, 1}) {  // two points on a wall facing +x: tx and rz become weak (relative eigenvalue < 1e-2)
    q2.emplace_back(-30.0, 10.0 * k - 4.0, 12.0);
    n2.emplace_back(1.0, 0.0, 0.0);
  }
  const DegeneracyReport weak = analyze_constraint(plane_normal_matrix(q2, n2), sigma, 0.02, 1.0);
  EXPECT_LT(weak.std(3), 0.02);
  ASSERT_EQ(weak.directions.size(), 1u);  // ty: free
  EXPECT_NEAR(std::abs(weak.directions[0].direction.y()), 1.0, 1e-9);
  const DegeneracyReport strict = analyze_constraint(plane_normal_matrix(q2, n2), sigma, 0.1 * weak.std(3), 1.0);
  EXPECT_EQ(strict.directions.size(), 2u);  // tx's std above the tolerance: held too
}

// The largest displacement std over points of the same plane: its estimated motions tz, rx, ry move a point at
// (dx, dy) from the centroid by tz + rx dy - ry dx along z, so the std there is sigma sqrt(1/N + dy^2/syy +
// dx^2/sxx) (independent: H is diagonal for the symmetric grid), largest at the corners; the held in-plane motions
// do not count.
TEST(Constraint, LargestDisplacementStdIsTheClosedFormOnAPlane) {
  const PlaneGrid grid = plane_grid();
  const std::vector<Eigen::Vector3d>&q = grid.q, &n = grid.n;
  const double sxx = grid.sxx, syy = grid.syy;
  const double sigma = 0.005, count = static_cast<double>(q.size());
  const DegeneracyReport r = analyze_constraint(plane_normal_matrix(q, n), sigma, 0.02, 0.01 * kDeg);
  const auto closed = [&](double dx, double dy) {
    return sigma * std::sqrt(1.0 / count + dy * dy / syy + dx * dx / sxx);
  };
  EXPECT_NEAR(largest_displacement_std_mm(r, {Eigen::Vector3d(7.0, -4.0, 10.0)}), closed(0, 0), 1e-12);
  EXPECT_NEAR(largest_displacement_std_mm(r, q), closed(30, 10), 1e-12);
  EXPECT_NEAR(largest_displacement_std_mm(r, {Eigen::Vector3d(107.0, -4.0, 10.0)}), closed(100, 0), 1e-12);
  EXPECT_EQ(largest_displacement_std_mm(r, {}), 0.0);
}

// The cluster-robust sandwich on the plane above, tz alone free: residuals +tau and -tau over alternate blocks of m
// points (a bias shared by each block) give g_b = +-m tau, so var(tz) = K/(K-1) sum_b g_b^2 / N^2 = tau^2 / (K-1),
// far above sigma^2 / N; the same residuals in a pattern that alternates within each block cancel in every g_b and
// leave sigma^2 / N. Independent residuals of std sigma: the cluster estimate is within its sampling spread
// (sqrt(2 / K) relative) of sigma^2 / N.
TEST(Constraint, ClusterSandwichSeesResidualsSharedOverABlock) {
  std::vector<Eigen::Vector3d> q, n;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 50; ++j) {
      q.emplace_back(2.0 * i, 3.0 * j, 5.0);  // block b = i / 2: 100 points, a compact strip
      n.emplace_back(0.0, 0.0, 1.0);
    }
  }
  const std::size_t K = 32, m = 100;
  const double count = static_cast<double>(q.size()), sigma = 0.005, tau = 0.05;
  FreeDof tz_only;
  tz_only.rx = tz_only.ry = tz_only.rz = tz_only.tx = tz_only.ty = false;
  std::vector<double> shared(q.size()), alternating(q.size()), independent(q.size());
  Random random(11);
  for (std::size_t k = 0; k < q.size(); ++k) {
    shared[k] = (k / m) % 2 == 0 ? tau : -tau;
    alternating[k] = k % 2 == 0 ? tau : -tau;
    independent[k] = sigma * random.normal();
  }
  const auto tz_std = [&](const std::vector<double>& psi) {
    PlaneNormalMatrix matrix = plane_normal_matrix(q, n);
    add_cluster_moment(q, n, psi, K, matrix);
    EXPECT_EQ(matrix.clusters, K);
    return analyze_constraint(matrix, sigma, 1.0, 1.0, tz_only).std(5);
  };
  EXPECT_NEAR(tz_std(shared), tau / std::sqrt(static_cast<double>(K - 1)), 1e-12);
  EXPECT_NEAR(tz_std(alternating), sigma / std::sqrt(count), 1e-12);
  EXPECT_NEAR(tz_std(independent), sigma / std::sqrt(count), 0.3 * sigma / std::sqrt(count));
  EXPECT_GE(tz_std(independent), sigma / std::sqrt(count));  // never below sigma^2 (N H)^-1
  // Fewer than 2 blocks: nothing added.
  PlaneNormalMatrix one = plane_normal_matrix(q, n);
  add_cluster_moment(q, n, shared, 1, one);
  EXPECT_EQ(one.clusters, 0u);
  EXPECT_NEAR(analyze_constraint(one, sigma, 1.0, 1.0, tz_only).std(5), sigma / std::sqrt(count), 1e-12);
}

// The robust fit's own bread (PlaneNormalMatrix::bread): when the kernel saturates three quarters of the pairs
// (spread over the plane alike), psi' sums to a quarter of H and var(tz) = sigma^2 / (N / 4): twice the std that
// counts every pair as information. What is held is decided on H as before.
TEST(Constraint, PairsTheKernelSaturatesAddNoInformation) {
  const PlaneGrid grid = plane_grid();
  const double sigma = 0.005, count = static_cast<double>(grid.q.size());
  FreeDof tz_only;
  tz_only.rx = tz_only.ry = tz_only.rz = tz_only.tx = tz_only.ty = false;
  PlaneNormalMatrix matrix = plane_normal_matrix(grid.q, grid.n);
  const DegeneracyReport all = analyze_constraint(matrix, sigma, 1.0, 1.0, tz_only);
  matrix.bread = 0.25 * matrix.H;
  const DegeneracyReport robust = analyze_constraint(matrix, sigma, 1.0, 1.0, tz_only);
  EXPECT_NEAR(all.std(5), sigma / std::sqrt(count), 1e-12);
  EXPECT_NEAR(robust.std(5), 2.0 * sigma / std::sqrt(count), 1e-12);
  // All six free: the in-plane motions are held alike with and without the bread.
  PlaneNormalMatrix free_matrix = plane_normal_matrix(grid.q, grid.n);
  const std::size_t held = analyze_constraint(free_matrix, sigma, 0.02, 0.01 * kDeg).directions.size();
  free_matrix.bread = 0.25 * free_matrix.H;
  const DegeneracyReport r = analyze_constraint(free_matrix, sigma, 0.02, 0.01 * kDeg);
  EXPECT_EQ(r.directions.size(), held);
  EXPECT_NEAR(r.std(0), 2.0 * sigma / std::sqrt(grid.syy), 1e-12);
}

struct PlatePair {
  std::vector<Eigen::Vector3d> scan;       // in the scan frame
  std::vector<Eigen::Vector3d> reference;  // in the reference frame
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
};

// Two independent samplings of the plate; the scan moved by `angle` about a tilted axis and `shift` (the issue's
// pair: 2 deg, 3.7 mm).
PlatePair plate_pair(RibbedPlateOptions o, std::uint64_t seed, double angle_rad, double shift_mm) {
  o.seed = 2 * seed;
  PlatePair pair;
  pair.reference = ribbed_plate_samples(o);
  o.seed = 2 * seed + 1;
  const std::vector<Eigen::Vector3d> scan_ref = ribbed_plate_samples(o);
  Eigen::Isometry3d T_scan_ref = Eigen::Isometry3d::Identity();
  T_scan_ref.linear() = Eigen::AngleAxisd(angle_rad, Eigen::Vector3d(0.3, 0.5, 1.0).normalized()).toRotationMatrix();
  T_scan_ref.translation() = shift_mm * Eigen::Vector3d(0.6, 0.8, 0.0);
  pair.scan = test::transformed_points(scan_ref, T_scan_ref);
  pair.T_ref_scan = T_scan_ref.inverse();
  return pair;
}

// The issue's pair: 100k points each, 0.02 mm noise, 2 deg / 3.7 mm apart, point-to-plane. A relative eigenvalue
// threshold held the translation along the ribs (1.38 mm error); its predicted std is micrometres. A Matrix suite: 100k
// points are too slow for the sanitizer stage.
TEST(ConstraintMatrix, RibbedPlateIssuePairWeakDirectionIsFitted) {
  RibbedPlateOptions plate;
  plate.points = 100000;
  const PlatePair pair = plate_pair(plate, 1, 2.0 * kDeg, 3.7);
  const IcpReference reference(to_cloud(pair.reference));
  IcpOptions options;
  options.max_correspondence_distance_mm = 20.0;
  const IcpResult r = icp(pair.scan, reference, Eigen::Isometry3d::Identity(), options);
  const double t_err = test::translation_error_mm(r.T_ref_scan, pair.T_ref_scan);
  const double r_err = test::rotation_error_deg(r.T_ref_scan, pair.T_ref_scan);
  const Eigen::Vector3d dt = r.T_ref_scan.translation() - pair.T_ref_scan.translation();
  std::printf(
      "  ribbed plate: %.5f mm (%.5f %.5f %.5f), %.6f deg, %d iterations (%s), noise %.4f mm, std t %.2e %.2e "
      "%.2e mm\n",
      t_err, dt.x(), dt.y(), dt.z(), r_err, r.iterations, to_string(r.termination), r.degeneracy.noise_mm,
      r.degeneracy.std(3), r.degeneracy.std(4), r.degeneracy.std(5));
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.degeneracy.degenerate());  // fitted, not held (held: 1.38 mm off)
  // The ribs' 1 mm ends are sampled at 0.55 mm spacing: point-to-plane against the reference cloud's PCA normals is
  // biased there by ~0.01-0.07 mm over seeds, and the sandwich covariance says so (std along y ~0.025 mm).
  EXPECT_LT(t_err, 0.05);
  EXPECT_LT(r_err, 0.01);
  EXPECT_LT(std::abs(dt.y()), 3.0 * r.degeneracy.std(4));
  // The noise estimate: the two samplings' 0.02 mm combine to ~0.028 mm along the normal.
  EXPECT_NEAR(r.degeneracy.noise_mm, 0.02 * std::sqrt(2.0), 0.008);
  // The weak direction (along the ribs) is known to hundredths of a millimetre, not to nothing; the others better.
  EXPECT_GT(r.degeneracy.std(4), 1e-3);
  EXPECT_LT(r.degeneracy.std(4), 0.1);
  EXPECT_LT(r.degeneracy.std(5), 1e-3);
}

// Ten seeds of a quarter of the plate (two ribs) at the issue's density (3.3 points per mm^2, 25k points): the weak
// direction is fitted every time, within three of its reported standard deviations, and never held.
TEST(ConstraintMatrix, RibbedPlateSeeds) {
  RibbedPlateOptions plate;
  plate.length_mm = 100.0;
  plate.width_mm = 75.0;
  plate.ribs = 2;
  plate.rib_length_mm = 50.0;
  plate.points = 25000;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const PlatePair pair = plate_pair(plate, 100 + seed, 2.0 * kDeg, 3.7);
    const IcpReference reference(to_cloud(pair.reference));
    IcpOptions options;
    options.max_correspondence_distance_mm = 20.0;
    const IcpResult r = icp(pair.scan, reference, Eigen::Isometry3d::Identity(), options);
    const Eigen::Vector3d dt = r.T_ref_scan.translation() - pair.T_ref_scan.translation();
    std::printf("  quarter plate seed %d: error y %.4f mm, std y %.4f mm (%.1f std)\n", static_cast<int>(seed), dt.y(),
                r.degeneracy.std(4), std::abs(dt.y()) / r.degeneracy.std(4));
    EXPECT_TRUE(r.converged);
    EXPECT_FALSE(r.degeneracy.degenerate());
    EXPECT_LT(dt.norm(), 0.1);
    EXPECT_LT(std::abs(dt.y()), 3.0 * r.degeneracy.std(4) + 0.005);
    // The rotation about z rests on 50 mm of rib flank: its error stays within the reported std's reach.
    const double std_deg = r.degeneracy.std.head<3>().maxCoeff() / kDeg;
    EXPECT_LT(test::rotation_error_deg(r.T_ref_scan, pair.T_ref_scan), std::min(0.05, 4.0 * std_deg + 0.005));
  }
}

// A noisy tube patch against its nominal mesh, ten seeds: the axis shift and turn are free (held at the start, the
// truth here), every other motion fitted; the held ones' reported std is above the tolerances.
TEST(ConstraintMatrix, TubeAxisIsFreeForEverySeed) {
  TubeOptions tube;
  tube.radius_mm = 120.0;
  tube.length_mm = 160.0;
  tube.arc_rad = M_PI / 2.0;
  tube.edge_mm = 4.0;
  const IcpReference reference(generate_tube(tube).mesh);
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    tube.edge_mm = 3.0;
    tube.noise_mm = 0.03;
    tube.seed = seed;
    const std::vector<Eigen::Vector3d> scan = generate_tube(tube).mesh.vertices;
    IcpOptions options;
    options.max_correspondence_distance_mm = 10.0;
    const IcpResult r = icp(scan, reference, Eigen::Isometry3d::Identity(), options);
    EXPECT_TRUE(r.converged);
    ASSERT_EQ(r.degeneracy.directions.size(), 2u);
    for (const DegenerateDirection& d : r.degeneracy.directions) {
      EXPECT_NEAR(std::abs(d.direction.z()), 1.0, 1e-2);  // the tube's axis is z
      EXPECT_TRUE(d.kind == MotionKind::kTranslation ? d.std_mm > options.free_tolerance_mm
                                                     : d.std_rad > options.free_tolerance_rad);
    }
    EXPECT_LT(r.T_ref_scan.translation().norm(), 0.05);
    EXPECT_LT(test::rotation_error_deg(r.T_ref_scan, Eigen::Isometry3d::Identity()), 0.01);
  }
}

// The surface noise estimate on a noisy plane and on a noisy ribbed plate: the noise along the normal, within 15 %.
TEST(SurfaceNoise, RecoversTheNoiseOfAPlaneAndThePlate) {
  Random random(5);
  std::vector<Eigen::Vector3d> plane(20000);
  for (Eigen::Vector3d& p : plane)
    p = Eigen::Vector3d(random.uniform(0, 100), random.uniform(0, 100), 0.05 * random.normal());
  EXPECT_NEAR(estimate_surface_noise(plane), 0.05, 0.0075);
  RibbedPlateOptions o;
  o.points = 20000;
  o.noise_mm = 0.05;
  EXPECT_NEAR(estimate_surface_noise(ribbed_plate_samples(o)), 0.05, 0.0075);
  EXPECT_EQ(estimate_surface_noise(std::vector<Eigen::Vector3d>(3, Eigen::Vector3d::Zero())), 0.0);
  SurfaceNoiseOptions bad;
  bad.neighbours = 2;
  EXPECT_THROW(estimate_surface_noise(plane, bad), Error);
}

}  // namespace
}  // namespace conform
