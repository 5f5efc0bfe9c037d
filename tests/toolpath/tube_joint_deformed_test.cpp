// Deformed tubes (ovality 1% of D, peaking at the seam 3 mm, bumps), 5 mm mesh, 0.2 mm noise: the path against the
// ground truth of generate_tube_joint (root-finding on the exact deformed surfaces, independent of the meshes), and
// the gap a cut computed on nominal cylinders would leave against the real leg.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/datasets/tube_surface.h"
#include "conform/toolpath/saddle/saddle_curve.h"
#include "tube_joint_fixture.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

TubeJointOptions deformed(const test::JointCase& c) {
  TubeJointOptions o = test::joint_options(c);
  o.leg.ovality_mm = 0.01 * 2.0 * c.leg_radius_mm / 4.0;  // D_max - D_min = 4a = 1% of D
  o.leg.ovality_azimuth_rad = 20.0 * kDeg;
  o.leg.seam_height_mm = 3.0;
  o.leg.seam_width_mm = 150.0;           // peaking spreads over a hand span either side of the weld
  o.leg.seam_azimuth_rad = 15.0 * kDeg;  // under the joint, where it matters
  o.leg.bumps.push_back({-10.0 * kDeg, 60.0, 2.0, 50.0});
  o.stub.ovality_mm = 0.01 * 2.0 * c.stub_radius_mm / 4.0;
  o.stub.ovality_azimuth_rad = 50.0 * kDeg;
  o.stub.seam_height_mm = 3.0;
  o.stub.seam_width_mm = 100.0;
  o.stub.seam_azimuth_rad = 100.0 * kDeg;
  o.leg.edge_mm = 5.0;
  o.stub.edge_mm = 5.0;
  o.leg.noise_mm = 0.2;
  o.stub.noise_mm = 0.2;
  return o;
}

class DeformedJoint : public ::testing::TestWithParam<test::JointCase> {};

TEST_P(DeformedJoint, PathIsWithinHalfAMillimetreOfTheTruthAndCloserToTheRealLegThanANominalCut) {
  const test::JointCase c = GetParam();
  const TubeJointOptions options = deformed(c);
  const TubeJointScans scans = generate_tube_joint(options);
  const TubeJointSpec spec = test::joint_spec(c);
  TubeJointSolveOptions solve;
  solve.sampling.step_rad = 1.0 * kDeg;
  solve.sampling.smoothing_rms_mm = 0.1;
  const TubeJointSolution solution = solve_tube_joint(scans.leg_L, scans.stub_S, T_L_S(spec).inverse(), solve);
  ASSERT_TRUE(solution.ok) << solution.termination;
  double path_truth = 0.0;
  double path_gap = 0.0;
  double worst_phi = 0.0;
  for (const PathFrame& f : solution.frames) {
    const double d = distance_to_truth(scans.truth, f.point);
    if (d > path_truth) worst_phi = f.phi_rad / kDeg;
    path_truth = std::max(path_truth, d);
    path_gap = std::max(path_gap, std::abs(leg_surface_distance(scans.truth, options.T_L_S, f.point)));
  }
  // The nominal cut: the analytic curve of the nominal cylinders, cut into the real stub at the same azimuth and
  // height on its wall; its gap is the real leg's distance from that edge.
  SaddleGeometry geometry;
  geometry.leg_radius_mm = c.leg_radius_mm;
  geometry.pipe_radius_mm = c.stub_radius_mm;
  geometry.pitch_rad = spec.pitch_rad;
  geometry.offset_mm = spec.offset_mm;
  const SaddleCurve nominal(geometry);
  double nominal_gap = 0.0;
  for (int k = 0; k < 360; ++k) {
    const double phi = 2.0 * kPi * k / 360;
    const double z_S = (T_S_P(spec) * nominal.point(phi)).z();
    const TubeOptions& stub = scans.truth.stub;
    const Eigen::Vector3d edge =
        scans.truth.T_S_stub_tube * tube_surface_in_tube(stub, phi, z_S - 0.5 * stub.length_mm).point;
    nominal_gap = std::max(nominal_gap, std::abs(leg_surface_distance(scans.truth, options.T_L_S, edge)));
  }
  // The paper's path (no refinement onto the local surface fits), for comparison.
  solve.geometry.k_refine = 0;
  const TubeJointSolution paper = solve_tube_joint(scans.leg_L, scans.stub_S, T_L_S(spec).inverse(), solve);
  double paper_truth = 0.0;
  for (const PathFrame& f : paper.frames) paper_truth = std::max(paper_truth, distance_to_truth(scans.truth, f.point));
  std::printf("worst at %.1f deg; without refinement: path to truth max %.3f mm\n", worst_phi, paper_truth);
  std::printf("pitch %g offset %g: path to truth max %.3f mm; gap to the real leg: path %.3f mm, nominal cut %.3f mm\n",
              c.pitch_deg, c.offset_mm, path_truth, path_gap, nominal_gap);
  EXPECT_LE(path_truth, 0.5);  // the bound
  EXPECT_LT(path_gap, 0.5);
  EXPECT_GT(nominal_gap, 4.0 * path_gap);  // the reason the job exists
}

INSTANTIATE_TEST_SUITE_P(PitchAndOffset, DeformedJoint,
                         ::testing::Values(test::JointCase{90.0, 0.0, 600.0, 300.0, 5.0},
                                           test::JointCase{45.0, 80.0, 600.0, 300.0, 5.0}));

}  // namespace
}  // namespace conform
