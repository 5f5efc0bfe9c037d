// Fine ICP (registration/icp.h): exact on noise-free full overlap for every variant, termination reasons, locked
// degrees of freedom, trimming, robust kernels, and the same bits for any number of threads.

#include "conform/registration/icp.h"

#include <omp.h>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/datasets/parts.h"
#include "convergence.h"
#include "registration_test_util.h"

namespace conform {
namespace {

using test::kDeg;

constexpr IcpMethod kMethods[] = {IcpMethod::kPointToPoint, IcpMethod::kPointToPlane, IcpMethod::kPointToSurface,
                                   IcpMethod::kPlaneToPlane};

Mesh part(bool box, double edge_mm, double noise_mm = 0.0, std::uint64_t seed = 1) {
  PartOptions options;
  options.edge_mm = edge_mm;
  options.noise_mm = noise_mm;
  options.seed = seed;
  return box ? box_part(options) : freeform_surface(options);
}

TEST(Icp, NoiseFreeFullOverlapIsExactForEveryVariant) {
  Random random(11);
  for (bool box : {true, false}) {
    const Mesh reference = part(box, 5.0);
    const IcpReference ref(reference);
    const Eigen::Vector3d centre = test::mean_point(reference.vertices);
    for (IcpMethod method : kMethods) {
      double worst_rotation_deg = 0.0, worst_translation_mm = 0.0;
      for (int trial = 0; trial < 3; ++trial) {
        // The scan is the reference's own vertices seen from another frame: T_ref_scan = truth. Point-to-point
        // starts within half a grid spacing: on two identical samplings, the pose shifted by one spacing is a local
        // minimum of nearest-vertex distances (only the borders disagree), where it stops from farther away.
        const bool p2p = method == IcpMethod::kPointToPoint;
        const Eigen::Isometry3d truth = test::random_motion(random, (p2p ? 1.0 : 5.0) * kDeg, p2p ? 1.0 : 8.0, centre);
        const std::vector<Eigen::Vector3d> scan = test::transformed_points(reference.vertices, truth.inverse());
        IcpOptions options;
        options.method = method;
        options.max_iterations = 100;
        options.max_correspondence_distance_mm = 30.0;
        const IcpResult r = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
        SCOPED_TRACE(std::string(box ? "box " : "freeform ") + to_string(method) + " trial " + std::to_string(trial));
        EXPECT_TRUE(r.converged) << to_string(r.termination);
        EXPECT_LT(test::rotation_error_deg(r.T_ref_scan, truth), 1e-6);
        EXPECT_LT(test::translation_error_mm(r.T_ref_scan, truth), 1e-6);
        EXPECT_LT(r.rms_mm, 1e-4);  // at the start of the last step, which moved less than 1e-4 mm
        EXPECT_EQ(r.inlier_fraction, 1.0);
        EXPECT_FALSE(r.degeneracy.degenerate());
        worst_rotation_deg = std::max(worst_rotation_deg, test::rotation_error_deg(r.T_ref_scan, truth));
        worst_translation_mm = std::max(worst_translation_mm, test::translation_error_mm(r.T_ref_scan, truth));
      }
      std::printf("  %-9s %-16s worst of 3: rotation %.1e deg, translation %.1e mm\n", box ? "box" : "free-form",
                  to_string(method), worst_rotation_deg, worst_translation_mm);
    }
  }
}

TEST(Icp, SaysWhyItStopped) {
  const Mesh reference = part(true, 6.0);
  const IcpReference ref(reference);
  const Eigen::Isometry3d truth =
      test::random_motion(*std::make_unique<Random>(2), 4.0 * kDeg, 6.0, test::mean_point(reference.vertices));
  const std::vector<Eigen::Vector3d> scan = test::transformed_points(reference.vertices, truth.inverse());
  IcpOptions options;
  options.max_correspondence_distance_mm = 30.0;
  options.max_iterations = 1;
  IcpResult r = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.termination, IcpTermination::kMaxIterations);
  EXPECT_EQ(r.iterations, 1);

  // No overlap: the scan a metre away finds nothing within 30 mm.
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(1000.0, 0.0, 0.0);
  options.max_iterations = 50;
  r = icp(scan, ref, far, options);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.termination, IcpTermination::kTooFewCorrespondences);
  EXPECT_EQ(r.inlier_fraction, 0.0);
  EXPECT_STREQ(to_string(r.termination), "too_few_correspondences");

  // Only a sliver of the scan meets the reference: converged on it, but reported as not.
  std::vector<Eigen::Vector3d> mostly_elsewhere = scan;
  for (std::size_t i = 0; i < mostly_elsewhere.size(); ++i) {
    if (i % 10 != 0) mostly_elsewhere[i] += Eigen::Vector3d(500.0, 0.0, 0.0);
  }
  options.min_inlier_fraction = 0.2;
  r = icp(mostly_elsewhere, ref, truth, options);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.termination, IcpTermination::kInsufficientOverlap);
  EXPECT_NEAR(r.inlier_fraction, 0.1, 0.01);
}

TEST(Icp, LockedRotationsStayLocked) {
  // A turntable: rotation about z and translation in x and y only.
  const Mesh reference = part(false, 5.0);
  const IcpReference ref(reference);
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.linear() = Eigen::AngleAxisd(4.0 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  truth.translation() = Eigen::Vector3d(3.0, -2.0, 0.0);
  const std::vector<Eigen::Vector3d> scan = test::transformed_points(reference.vertices, truth.inverse());
  for (IcpMethod method : kMethods) {
    IcpOptions options;
    options.method = method;
    options.max_iterations = 100;
    options.free_dof.rx = options.free_dof.ry = options.free_dof.tz = false;
    const IcpResult r = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
    SCOPED_TRACE(to_string(method));
    EXPECT_TRUE(r.converged);
    EXPECT_LT((r.T_ref_scan.linear().col(2) - Eigen::Vector3d::UnitZ()).norm(), 1e-14);
    EXPECT_LT(std::abs(r.T_ref_scan.translation().z()), 1e-12);
    EXPECT_LT(test::rotation_error_deg(r.T_ref_scan, truth), 1e-6);
    EXPECT_LT(test::translation_error_mm(r.T_ref_scan, truth), 1e-6);
    EXPECT_EQ(r.degeneracy.eigenvalues.size(), 3);
  }
}

TEST(Icp, TrimmingAndKernelsResistOutliersAndPartialOverlap) {
  // The scan: a noisy copy of the free-form surface, 10% of it moved 3-6 mm off the surface, and a patch the
  // reference lacks (the reference is cut at x < 60).
  const Mesh full = part(false, 4.0, 0.02, 5);
  Mesh cut = part(false, 3.0);
  Mesh reference;
  for (const Eigen::Vector3d& v : cut.vertices) {
    if (v.x() < 60.0) reference.vertices.push_back(v);
  }
  const IcpReference ref(reference);
  Random random(8);
  const Eigen::Isometry3d truth = test::random_motion(random, 3.0 * kDeg, 5.0, Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> points = full.vertices;
  for (std::size_t i = 0; i < points.size(); i += 10) points[i] += random.uniform(3.0, 6.0) * full.normals[i];
  const std::vector<Eigen::Vector3d> scan = test::transformed_points(points, truth.inverse());

  struct Variant {
    const char* name;
    double overlap;
    RobustKernel kernel;
    double max_rotation_deg, max_translation_mm;
  };
  const Variant variants[] = {{"trimmed 0.7 + tukey", 0.7, RobustKernel::kTukey, 0.01, 0.02},
                              {"huber", 1.0, RobustKernel::kHuber, 0.05, 0.1},
                              {"tukey", 1.0, RobustKernel::kTukey, 0.01, 0.02}};
  for (const Variant& v : variants) {
    IcpOptions options;
    options.max_correspondence_distance_mm = 20.0;
    options.overlap = v.overlap;
    options.kernel = v.kernel;
    options.max_iterations = 100;
    const IcpResult r = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
    std::printf("  %-20s rotation %.5f deg, translation %.5f mm, rms %.4f mm, inliers %.3f, %d iterations\n", v.name,
                test::rotation_error_deg(r.T_ref_scan, truth), test::translation_error_mm(r.T_ref_scan, truth),
                r.rms_mm, r.inlier_fraction, r.iterations);
    EXPECT_TRUE(r.converged) << v.name;
    EXPECT_LT(test::rotation_error_deg(r.T_ref_scan, truth), v.max_rotation_deg) << v.name;
    EXPECT_LT(test::translation_error_mm(r.T_ref_scan, truth), v.max_translation_mm) << v.name;
  }
}

TEST(Icp, SameBitsForAnyNumberOfThreads) {
  const Mesh reference = part(true, 4.0);
  const IcpReference ref(reference);
  const Mesh scan_mesh = part(true, 3.0, 0.05, 3);
  Random random(4);
  const Eigen::Isometry3d truth = test::random_motion(random, 4.0 * kDeg, 6.0, Eigen::Vector3d::Zero());
  const std::vector<Eigen::Vector3d> scan = test::transformed_points(scan_mesh.vertices, truth.inverse());
  for (IcpMethod method : kMethods) {
    IcpOptions options;
    options.method = method;
    omp_set_num_threads(1);
    const IcpResult one = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
    omp_set_num_threads(2);
    const IcpResult two = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
    EXPECT_EQ(one.T_ref_scan.matrix(), two.T_ref_scan.matrix()) << to_string(method);
    EXPECT_EQ(one.iterations, two.iterations);
  }
}

TEST(Icp, BadInputThrows) {
  const IcpReference ref(part(false, 10.0));
  IcpOptions options;
  EXPECT_THROW(icp({}, ref, Eigen::Isometry3d::Identity(), options), Error);
  EXPECT_THROW(icp({{0.0, 0.0, NAN}}, ref, Eigen::Isometry3d::Identity(), options), Error);
  options.overlap = 0.0;
  EXPECT_THROW(icp({{0.0, 0.0, 0.0}}, ref, Eigen::Isometry3d::Identity(), options), Error);
  Mesh cloud = part(false, 10.0);
  cloud.faces.clear();
  const IcpReference no_faces(cloud);
  options = IcpOptions{};
  options.method = IcpMethod::kPointToSurface;
  EXPECT_THROW(icp({{0.0, 0.0, 0.0}}, no_faces, Eigen::Isometry3d::Identity(), options), Error);
}

// Eq. (1) of convergence.h on a normal matrix H = I (N = 100 pairs, sigma = 1 mm, L = 1 mm): a step moving by t mm
// along x has m = sqrt(N) t / sigma = 10 t.
detail::ConvergenceTest convergence_on_unit_matrix(PlaneNormalMatrix& plane) {
  plane.H = Matrix6d::Identity();
  plane.count = 100;
  plane.length_scale_mm = 1.0;
  return detail::ConvergenceTest(0.25, 1e-9, 1e-9);
}

Eigen::Isometry3d shift_x(double mm) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(mm, 0.0, 0.0);
  return T;
}

TEST(IcpConvergence, AStepIsConvergedBelowAFractionOfThePredictedStd) {
  PlaneNormalMatrix plane;
  detail::ConvergenceTest small = convergence_on_unit_matrix(plane);
  EXPECT_TRUE(small.converged(shift_x(0.02), plane, 1.0));  // m = 0.2 <= 0.25
  EXPECT_NEAR(small.last_std_fraction(), 0.2, 1e-12);
  detail::ConvergenceTest large = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(large.converged(shift_x(0.03), plane, 1.0));  // m = 0.3
  // The same step against four times the noise is a quarter as long in std: converged.
  detail::ConvergenceTest noisy = convergence_on_unit_matrix(plane);
  EXPECT_TRUE(noisy.converged(shift_x(0.03), plane, 4.0));
  // Repeated the same way it is a motion under way (rho = 1): not converged.
  EXPECT_FALSE(noisy.converged(shift_x(0.03), plane, 4.0));
}

TEST(IcpConvergence, SteadyCreepIsNotConvergedAndACycleIs) {
  PlaneNormalMatrix plane;
  detail::ConvergenceTest creep = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(creep.converged(shift_x(0.03), plane, 1.0));
  // 0.019 after 0.020 the same way: rho 0.95, 0.19 x 0.95 / 0.05 = 3.6 std still to come.
  EXPECT_FALSE(creep.converged(shift_x(0.020), plane, 1.0));
  EXPECT_FALSE(creep.converged(shift_x(0.019), plane, 1.0));
  // Halving steps: 0.02 then 0.01: 0.1 + 0.1 x 0.5 / 0.5 = 0.2 <= 0.25.
  detail::ConvergenceTest halving = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(halving.converged(shift_x(0.05), plane, 1.0));
  EXPECT_TRUE(halving.converged(shift_x(0.025), plane, 1.0) ||
              halving.converged(shift_x(0.0125), plane, 1.0));
  // Back and forth by 0.02 (pairs flipping): each step 0.2 std, no motion under way: converged.
  detail::ConvergenceTest cycle = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(cycle.converged(shift_x(0.04), plane, 1.0));
  EXPECT_TRUE(cycle.converged(shift_x(-0.02), plane, 1.0));
}

// A creep (steps the same way, shrinking) is to be jumped by the geometric series' sum 1 / (1 - rho), capped; a
// cycle or a growing step is not. The step after a jump is judged with the rate measured before it.
TEST(IcpConvergence, ACreepIsJumpedByTheSumOfItsSeries) {
  PlaneNormalMatrix plane;
  detail::ConvergenceTest creep = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(creep.converged(shift_x(0.04), plane, 1.0));
  EXPECT_EQ(creep.jump_factor(3.0), 1.0);  // one step: no rate yet
  EXPECT_FALSE(creep.converged(shift_x(0.03), plane, 1.0));
  EXPECT_TRUE(creep.creeping());
  EXPECT_NEAR(creep.jump_factor(10.0), 4.0, 1e-9);  // rho 0.75
  EXPECT_NEAR(creep.jump_factor(3.0), 3.0, 1e-12);
  creep.jumped();
  // After the jump a step of 0.008 (m = 0.08) is judged with rho 0.75: 0.08 + 0.24 still to come, not converged
  // (its ratio to the step before, 0.27, would say 0.08 + 0.03: converged).
  EXPECT_FALSE(creep.converged(shift_x(0.008), plane, 1.0));
  EXPECT_FALSE(creep.creeping());
  detail::ConvergenceTest cycle = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(cycle.converged(shift_x(0.04), plane, 1.0));
  EXPECT_FALSE(cycle.converged(shift_x(-0.03), plane, 1.0));
  EXPECT_EQ(cycle.jump_factor(3.0), 1.0);
  detail::ConvergenceTest growing = convergence_on_unit_matrix(plane);
  EXPECT_FALSE(growing.converged(shift_x(0.03), plane, 1.0));
  EXPECT_FALSE(growing.converged(shift_x(0.04), plane, 1.0));
  EXPECT_EQ(growing.jump_factor(3.0), 1.0);
}

TEST(IcpConvergence, AScaledMotionTurnsAndMovesItsCentreThatManyTimesOver) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  delta.linear() = Eigen::AngleAxisd(0.01, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  delta.translation() = Eigen::Vector3d(0.3, -0.2, 0.1);
  const Eigen::Vector3d centre(40.0, -10.0, 5.0);
  EXPECT_TRUE(detail::scaled_motion(delta, centre, 1.0).isApprox(delta, 1e-12));
  const Eigen::Isometry3d triple = detail::scaled_motion(delta, centre, 3.0);
  EXPECT_NEAR(rotation_angle(triple), 0.03, 1e-12);
  EXPECT_LT(((triple * centre - centre) - 3.0 * (delta * centre - centre)).norm(), 1e-12);
  // About its centre, a twist taken three times is the same axis.
  EXPECT_LT((Eigen::AngleAxisd(triple.linear()).axis() - Eigen::Vector3d(1, 2, 3).normalized()).norm(), 1e-9);
}

TEST(IcpConvergence, TheTolerancesAreTheFloorOfANoiseFreeFit) {
  PlaneNormalMatrix plane;
  plane.H = Matrix6d::Identity();
  plane.count = 100;
  plane.length_scale_mm = 1.0;
  detail::ConvergenceTest floor(0.0, 1e-6, 1e-4);  // no std rule: only the tolerances
  EXPECT_TRUE(floor.converged(shift_x(5e-5), plane, 1e-3));
  EXPECT_FALSE(floor.converged(shift_x(2e-4), plane, 1e-3));
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() = Eigen::AngleAxisd(2e-6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_FALSE(floor.converged(turn, plane, 1e-3));
}

// A noisy pair (0.1 mm noise, where the old 1e-4 mm step rule ran out of iterations on profiler data) converges, and
// the pose lands within 4 of its own predicted std.
TEST(IcpConvergence, ANoisyFitConvergesWithinItsPredictedStd) {
  const Mesh reference = part(true, 4.0);
  Random random(7);
  std::vector<Eigen::Vector3d> scan = part(true, 3.0, 0.1, 7).vertices;
  const Eigen::Isometry3d truth = test::random_motion(random, 1.0 * kDeg, 1.0, test::mean_point(scan));
  scan = test::transformed_points(scan, truth.inverse());
  const IcpReference ref(reference);
  IcpOptions options;
  options.max_correspondence_distance_mm = 10.0;
  options.method = IcpMethod::kPointToSurface;
  const IcpResult r = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
  ASSERT_TRUE(r.converged) << to_string(r.termination);
  EXPECT_LE(r.last_step_std, 0.25);
  EXPECT_LT(r.iterations, 50);
  const Eigen::Vector3d c = r.degeneracy.centre;
  const Eigen::Isometry3d error = r.T_ref_scan * truth.inverse();
  const Eigen::Vector3d moved = error * c - c;
  for (int i = 0; i < 3; ++i) EXPECT_LE(std::abs(moved(i)), 4.0 * r.degeneracy.std(3 + i) + 1e-4) << i;
}

}  // namespace
}  // namespace conform
