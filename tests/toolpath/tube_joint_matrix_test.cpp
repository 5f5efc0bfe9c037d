// Realistic variation (the matrix): pitch 20-90 deg, offset up to 0.95 (R - r), meshes 1-10 mm, noise
// 0-0.5 mm, ovality 0-2 % of D, peaking 0-5 mm; five seeds at each of a handful of corners of that space. Every run
// either gives a path within a stated bound of the ground truth (generate_tube_joint's root-finding on the exact
// deformed surfaces), or fails with one of the diagnoses allowed for that corner: never a closed path that is off.
//
// The bound is scaled by the scans: 0.05 mm + the two facet sagittas + 2 sigma / sin(beta), beta the smallest angle
// between the surfaces along the path (where the surfaces cross at a shallow angle, noise of sigma normal to them
// moves the seam by sigma / sin beta along them).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "tube_joint_fixture.h"

#include "conform/core/constants.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

struct Corner {
  const char* name;
  double pitch_deg;
  double offset_fraction;  // of R - r
  double leg_radius_mm;
  double stub_radius_mm;
  double edge_mm;
  double noise_mm;
  double ovality_pct;
  double peaking_mm;
  int must_pass;                           // of the five seeds
  std::set<std::string> allowed_failures;  // diagnoses allowed when a seed does not pass
  double max_direction_error_deg = 2.0;    // the solve's [directions] limit (this matrix checks positions)
};

TubeJointOptions corner_options(const Corner& k, unsigned seed) {
  test::JointCase c;
  c.pitch_deg = k.pitch_deg;
  c.offset_mm = k.offset_fraction * (k.leg_radius_mm - k.stub_radius_mm);
  c.leg_radius_mm = k.leg_radius_mm;
  c.stub_radius_mm = k.stub_radius_mm;
  c.edge_mm = k.edge_mm;
  TubeJointOptions o = test::joint_options(c);
  for (TubeOptions* tube : {&o.leg, &o.stub}) {
    tube->ovality_mm = k.ovality_pct / 100.0 * 2.0 * tube->radius_mm / 4.0;  // D_max - D_min = 4a
    tube->seam_height_mm = k.peaking_mm;
    tube->seam_width_mm = 100.0;
    tube->noise_mm = k.noise_mm;
  }
  o.leg.ovality_azimuth_rad = 20.0 * kDeg;
  o.leg.seam_azimuth_rad = 10.0 * kDeg;
  o.stub.ovality_azimuth_rad = 50.0 * kDeg;
  o.stub.seam_azimuth_rad = 100.0 * kDeg;
  o.leg.seed = 100 + 2 * seed;
  o.stub.seed = 101 + 2 * seed;
  return o;
}

void run_corner(const Corner& k) {
  int passed = 0;
  for (unsigned seed = 0; seed < 5; ++seed) {
    const TubeJointOptions options = corner_options(k, seed);
    const TubeJointScans scans = generate_tube_joint(options);
    TubeJointSolveOptions solve_options;
    solve_options.max_direction_error_deg = k.max_direction_error_deg;
    const TubeJointSolution s = solve_tube_joint(scans.leg_L, scans.stub_S, options.T_L_S.inverse(), solve_options);
    if (!s.ok) {
      std::printf("%s seed %u: exit 1, %s\n", k.name, seed, s.termination.c_str());
      EXPECT_TRUE(k.allowed_failures.count(s.check.condition) > 0)
          << k.name << " seed " << seed << ": " << s.termination;
      continue;
    }
    double worst = 0.0;
    double min_sin_beta = 1.0;
    for (const PathFrame& f : s.frames) {
      worst = std::max(worst, distance_to_truth(scans.truth, f.point));
      min_sin_beta = std::min(min_sin_beta, f.stub_normal.cross(f.leg_normal).norm());
    }
    const double sagitta = test::facet_sagitta(scans.truth.leg) + test::facet_sagitta(scans.truth.stub);
    const double bound = 0.05 + sagitta + 2.0 * k.noise_mm / min_sin_beta;
    std::printf(
        "%s seed %u: to truth max %.3f mm (bound %.3f; beta min %.1f deg; %zu islands, %zu backtracks "
        "dropped, max %.3f of %.3f mm; noise est leg %.3f stub %.3f; refined %zu of %zu)\n",
        k.name, seed, worst, bound, std::asin(min_sin_beta) / kDeg, s.islands, s.dropped_vertices, s.max_backtrack_mm,
        s.backtrack_tolerance_mm, s.leg_quality.noise_mm, s.stub_quality.noise_mm, s.refined_points, s.frames.size());
    EXPECT_LE(worst, bound) << k.name << " seed " << seed;
    ++passed;
  }
  EXPECT_GE(passed, k.must_pass) << k.name;
}

// The first case, scaled down 2x (R 300 / r 125, offset 0.94 (R - r): the surfaces cross at ~11 deg at the
// sides), 2 mm meshes, 0.2 mm noise: it failed 4 of 4 seeds before (islands, backtracks of 0.1-0.2 mm).
TEST(TubeJointMatrix, LargeOffsetFineNoisyMeshes) {
  run_corner({"pitch 45, offset 0.94, 2 mm, 0.2 mm noise", 45.0, 0.94, 300.0, 125.0, 2.0, 0.2, 1.0, 3.0, 5, {}});
}

// A T joint on 1 mm meshes with 0.2 mm noise (the issue: 3 of 3 failed).
TEST(TubeJointMatrix, TJointOneMillimetreMeshesNoisy) {
  run_corner({"pitch 90, offset 0, 1 mm, 0.2 mm noise", 90.0, 0.0, 150.0, 60.0, 1.0, 0.2, 0.0, 0.0, 5, {}});
}

// Shallow pitch, heavy deformation and noise on a 5 mm mesh.
TEST(TubeJointMatrix, ShallowPitchHeavyDeformation) {
  run_corner({"pitch 20, offset 0, 5 mm, 0.5 mm noise, 2 %, 5 mm", 20.0, 0.0, 600.0, 250.0, 5.0, 0.5, 2.0, 5.0, 5, {}});
}

// The stub's wall nearly tangent to the leg (offset 0.95 (R - r)) on a coarse 10 mm mesh with 0.5 mm noise. The seam
// tangent there is known to +-2.1-2.3 deg only (2 sigma; [directions] refuses it at the default 2 deg): this corner
// checks the path's position, with the direction limit at 5 deg.
TEST(TubeJointMatrix, NearTangentCoarseNoisy) {
  run_corner({"pitch 90, offset 0.95, 10 mm, 0.5 mm noise, 2 %, 5 mm",
              90.0,
              0.95,
              600.0,
              250.0,
              10.0,
              0.5,
              2.0,
              5.0,
              4,
              {"azimuth", "one-curve", "jordan"},
              5.0});
}

// Noise-free, undeformed, negative offset: the facet sagitta alone.
TEST(TubeJointMatrix, CleanNegativeOffset) {
  run_corner({"pitch 30, offset -0.5, 3 mm, clean", 30.0, -0.5, 400.0, 150.0, 3.0, 0.0, 0.0, 0.0, 5, {}});
}

}  // namespace
}  // namespace conform
