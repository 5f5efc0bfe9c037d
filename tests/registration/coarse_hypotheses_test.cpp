// Global registration that knows when it failed: several FPFH hypotheses and the principal-axes starts, each refined
// by a short ICP and scored by the share of the scan within a noise-scaled distance of the reference. A near-
// symmetric part (a plate with one small boss: turned 180 degrees it fits all but the boss) must come out as the
// right pose or as ambiguous (the align verdict's "no", exit 1), never the mirror pose unflagged; a clearly
// asymmetric partial scan (65 % of the box part) must come out at the right pose.

#include <gtest/gtest.h>

#include <cstdio>
#include <iterator>

#include "conform/core/error.h"
#include "conform/registration/coarse.h"
#include "boss_plate.h"
#include "registration_test_util.h"
#include "test_parts.h"

namespace conform {
namespace {


std::vector<Eigen::Vector3d> with_noise(std::vector<Eigen::Vector3d> points, double sigma, Random& random) {
  for (Eigen::Vector3d& p : points) p += sigma * Eigen::Vector3d(random.normal(), random.normal(), random.normal());
  return points;
}

CoarseOptions fpfh_options(double size_mm, std::uint64_t seed) {
  CoarseOptions coarse;
  coarse.method = CoarseMethod::kFpfh;
  coarse.multi_start.probe.max_correspondence_distance_mm = 0.1 * size_mm;
  coarse.fpfh.seed = seed;
  return coarse;
}

// What the align verdict accepts (exit 0) from the coarse step: not ambiguous, the best start on the reference.
bool accepted(const CoarseResult& c, double overlap) {
  const StartReport& best = c.ranking.starts[static_cast<std::size_t>(c.ranking.best)];
  return !c.ranking.ambiguous && best.inlier_share >= 0.5 * overlap;
}

struct Tally {
  int right = 0, refused = 0, wrong_accepted = 0;
};

// The boss plate under `seeds` random motions (any rotation): right, refused, or (the failure) wrong and accepted.
Tally boss_plate_trials(int seeds) {
  Mesh reference_mesh;
  reference_mesh.vertices = test::boss_plate(1.5, 0.0);
  const IcpReference reference(reference_mesh);
  Tally tally;
  for (int trial = 1; trial <= seeds; ++trial) {
    const int seed = test::matrix_seed(trial, seeds);
    Random random(static_cast<std::uint64_t>(100 + seed));
    const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 50.0, Eigen::Vector3d::Zero());
    const std::vector<Eigen::Vector3d> scan =
        test::transformed_points(with_noise(test::boss_plate(1.2, 0.4), 0.02, random), truth.inverse());
    const CoarseResult c = coarse_align(scan, reference, fpfh_options(145.0, static_cast<std::uint64_t>(seed)));
    const bool right = test::rotation_error_deg(c.T_ref_scan, truth) < 1.0;
    const bool ok = accepted(c, 1.0);
    const StartReport& best = c.ranking.starts[static_cast<std::size_t>(c.ranking.best)];
    const double runner = c.ranking.runner_up < 0
                              ? 0.0
                              : c.ranking.starts[static_cast<std::size_t>(c.ranking.runner_up)].inlier_share;
    std::printf("  boss plate seed %d: %s, best '%s' share %.3f (runner-up %.3f), %s, %zu starts, within %.3f mm\n",
                seed, right ? "right" : "WRONG", best.label.c_str(), best.inlier_share, runner,
                ok ? "accepted" : "refused", c.ranking.starts.size(), c.inlier_distance_mm);
    tally.right += right && ok;
    tally.refused += !ok;
    tally.wrong_accepted += !right && ok;
  }
  return tally;
}

// The box part's scan cut to about 65 % (the points on one side of a plane), under `seeds` random motions.
Tally partial_box_trials(int seeds) {
  const test::TestPart part = test::make_test_part(test::PartKind::kBox);
  const IcpReference reference(part.reference);
  Tally tally;
  for (int trial = 1; trial <= seeds; ++trial) {
    const int seed = test::matrix_seed(trial, seeds);
    Random random(static_cast<std::uint64_t>(200 + seed));
    const Eigen::Vector3d cut = test::random_direction(random);
    std::vector<double> heights;
    for (const Eigen::Vector3d& p : part.scan) heights.push_back(cut.dot(p - part.centre));
    std::vector<double> sorted = heights;
    const std::size_t k = sorted.size() * 65 / 100;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
    const double limit = sorted[k];
    std::vector<Eigen::Vector3d> kept;
    for (std::size_t i = 0; i < part.scan.size(); ++i) {
      if (heights[i] <= limit) kept.push_back(part.scan[i]);
    }
    const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 0.2 * part.size_mm, part.centre);
    const std::vector<Eigen::Vector3d> scan = test::transformed_points(kept, truth.inverse());
    const CoarseResult c = coarse_align(scan, reference, fpfh_options(part.size_mm, static_cast<std::uint64_t>(seed)));
    const double rot = test::rotation_error_deg(c.T_ref_scan, truth), tra = test::translation_error_mm(c.T_ref_scan, truth);
    const bool right = rot < 0.5 && tra < 0.5;
    const bool ok = accepted(c, 1.0);
    const StartReport& best = c.ranking.starts[static_cast<std::size_t>(c.ranking.best)];
    std::printf("  partial box seed %d: %.3f deg %.3f mm, best '%s' share %.3f, %s\n", seed, rot, tra,
                best.label.c_str(), best.inlier_share, ok ? "accepted" : "refused");
    tally.right += right && ok;
    tally.refused += !ok;
    tally.wrong_accepted += !right && ok;
  }
  return tally;
}

// The hypotheses are the best distinct RANSAC poses, best first; the same options give the same poses, and a
// different seed still finds the pose.
TEST(CoarseHypotheses, FpfhHypothesesAreSeededAndDistinct) {
  const test::TestPart part = test::make_test_part(test::PartKind::kBox);
  FpfhOptions options;
  options.hypotheses = 3;
  options.seed = 7;
  const FpfhResult a = fpfh_ransac(part.scan, part.reference.vertices, options);
  const FpfhResult b = fpfh_ransac(part.scan, part.reference.vertices, options);
  ASSERT_FALSE(a.hypotheses.empty());
  ASSERT_LE(a.hypotheses.size(), 3u);
  ASSERT_EQ(a.hypotheses.size(), b.hypotheses.size());
  for (std::size_t k = 0; k < a.hypotheses.size(); ++k) {
    EXPECT_TRUE(a.hypotheses[k].T_ref_scan.isApprox(b.hypotheses[k].T_ref_scan, 0.0));
    EXPECT_LE(a.hypotheses[k].inlier_fraction, a.inlier_fraction);  // the result is the best one
    for (std::size_t j = 0; j < k; ++j) {  // distinct: more than 1 degree or 5 inlier distances apart
      const Eigen::Isometry3d& p = a.hypotheses[j].T_ref_scan;
      const Eigen::Isometry3d& q = a.hypotheses[k].T_ref_scan;
      const Eigen::Vector3d c = test::mean_point(part.scan);
      EXPECT_TRUE(test::rotation_error_deg(p, q) > 1.0 || (p * c - q * c).norm() > 5.0 * 1.5 * a.voxel_mm);
    }
  }
  EXPECT_TRUE(a.found);
  EXPECT_GT(a.iterations, 0);
  EXPECT_LT(test::rotation_error_deg(a.T_ref_scan, Eigen::Isometry3d::Identity()), 2.0);  // scan and part coincide
  options.seed = 8;
  const FpfhResult c = fpfh_ransac(part.scan, part.reference.vertices, options);
  EXPECT_LT(test::rotation_error_deg(c.T_ref_scan, Eigen::Isometry3d::Identity()), 2.0);
}

// The match filters (mutual nearest features, the ratio test) thin the points RANSAC draws from and keep the pose;
// the outlier removal drops stray points before the voxels. Measured in align_matrix_test.cpp: the filters do not
// help (off by default), the outlier removal does.
TEST(CoarseHypotheses, FpfhMatchFiltersKeepThePose) {
  const test::TestPart part = test::make_test_part(test::PartKind::kBox);
  FpfhOptions options;
  options.hypotheses = 2;
  options.mutual = false;
  const FpfhResult plain = fpfh_ransac(part.scan, part.reference.vertices, options);
  options.mutual = true;
  options.ratio = 0.9;
  options.min_matched_points = 3;
  const FpfhResult filtered = fpfh_ransac(part.scan, part.reference.vertices, options);
  EXPECT_LT(filtered.matched_points, plain.matched_points);
  EXPECT_GE(filtered.matched_points, 3u);
  EXPECT_TRUE(filtered.found);
  // RANSAC's own pose, a voxel (6 mm here) or so from the truth before any ICP: within a few degrees.
  EXPECT_LT(test::rotation_error_deg(filtered.T_ref_scan, Eigen::Isometry3d::Identity()), 5.0);
  options.ratio = 1.5;
  EXPECT_THROW(fpfh_ransac(part.scan, part.reference.vertices, options), Error);
}

// "Fpfh" in the names: sanitizer runs can leave PCL's feature objects out with --gtest_filter=-*Fpfh* (see
// align_pipeline_test.cpp).
TEST(CoarseHypotheses, FpfhBossPlateIsRightOrRefused) {
  const Tally t = boss_plate_trials(1);
  EXPECT_EQ(t.wrong_accepted, 0);
}

TEST(CoarseHypotheses, FpfhPartialBoxIsRight) {
  const Tally t = partial_box_trials(1);
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_EQ(t.right, 1);
}

TEST(CoarseHypothesesMatrix, FpfhBossPlateTenSeeds) {
  const Tally t = boss_plate_trials(10);
  std::printf("  boss plate: %d right, %d refused, %d wrong and accepted\n", t.right, t.refused, t.wrong_accepted);
  EXPECT_EQ(t.wrong_accepted, 0);
}

TEST(CoarseHypothesesMatrix, FpfhPartialBoxTenSeeds) {
  const Tally t = partial_box_trials(10);
  std::printf("  partial box: %d right, %d refused, %d wrong and accepted\n", t.right, t.refused, t.wrong_accepted);
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_GE(t.right, 9);
}

// A tube R200 with a 16 mm wall, 600 mm long, its top cut as by a crossing tube (z up to 600 - 60 cos(azimuth)), a
// weld bead (3 mm high, 8 mm wide) along its outer wall at azimuth 60 deg, on a grid of `step` mm: the outer wall over
// azimuths [from, to) deg, and the inner wall too when `inner`.
std::vector<Eigen::Vector3d> beaded_tube(double from_deg, double to_deg, double step, bool inner) {
  std::vector<Eigen::Vector3d> out;
  for (const double radius : {200.0, 184.0}) {
    if (radius < 200.0 && !inner) break;
    const double dphi = step / radius;
    for (double phi = from_deg * M_PI / 180.0; phi < to_deg * M_PI / 180.0; phi += dphi) {
      const double across = radius * std::remainder(phi - M_PI / 3.0, 2.0 * M_PI);  // mm from the bead's middle
      const bool bead = radius == 200.0 && std::abs(across) < 4.0;
      const double r = radius + (bead ? 1.5 * (1.0 + std::cos(M_PI * across / 4.0)) : 0.0);
      for (double z = 0.0; z <= 600.0 - 60.0 * std::cos(phi); z += step) {
        out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
      }
    }
  }
  return out;
}

// A 120 deg arc of a tube in another frame: FPFH finds no hypothesis (a cylinder's features are all alike) and the
// arc's principal axes are not the tube's, so every start was 100+ mm off. The fitted cylinders' axes
// (cylinder_starts.h) give starts turned about the axis a few mm apart at the wall, the scan's ends at the tube's,
// screened by quick probes (rank_starts): the turn that puts the bead (2 % of the scan) on the bead and the cut end on
// the cut end is found. With 12 turns 30 deg apart and the scan's centroid on the tube's (the first try) both trials
// came back wrong (1 deg and 12.7 mm off along the axis: the cut end moves the centroid) and passed on.
TEST(CoarseHypotheses, ATubeArcStartsFromTheFittedAxes) {
  Mesh reference_mesh;
  reference_mesh.vertices = beaded_tube(0.0, 360.0, 3.0, true);
  const IcpReference reference(reference_mesh);
  for (int trial = 1; trial <= 2; ++trial) {
    Random random(static_cast<std::uint64_t>(700 + trial));
    const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 100.0, Eigen::Vector3d::Zero());
    const std::vector<Eigen::Vector3d> scan =
        test::transformed_points(with_noise(beaded_tube(0.0, 120.0, 1.5, false), 0.03, random), truth.inverse());
    const CoarseResult c = coarse_align(scan, reference, fpfh_options(700.0, static_cast<std::uint64_t>(trial)));
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : scan) centre += p / static_cast<double>(scan.size());
    // Within 1 deg and 1 mm at the scan's centre.
    const auto near_truth = [&](const Eigen::Isometry3d& T) {
      return test::rotation_error_deg(T, truth) < 1.0 && (T * centre - truth * centre).norm() < 1.0;
    };
    int right_from_axes = 0;
    for (const StartReport& s : c.ranking.starts) {
      right_from_axes += s.label.rfind("cylinder axis", 0) == 0 && near_truth(s.T_probe);
    }
    const bool right = near_truth(c.T_ref_scan);
    std::printf("tube arc, trial %d: %zu starts, %d from the axes right; best '%s' %s, %s\n", trial,
                c.ranking.starts.size(), right_from_axes,
                c.ranking.starts[static_cast<std::size_t>(c.ranking.best)].label.c_str(), right ? "right" : "WRONG",
                c.ranking.ambiguous ? "ambiguous" : "not ambiguous");
    EXPECT_GT(right_from_axes, 0) << trial;
    EXPECT_TRUE(right) << trial;
    EXPECT_TRUE(right || !accepted(c, 1.0)) << trial;  // never a wrong pose passed on as the coarse answer
  }
}

// The same tube arc over realistic variation, one seed a case: noise 0.1 mm, a coarse 3 mm scan, a 90 deg arc, a
// 180 deg arc. Never a wrong pose passed on as the coarse answer, and the right one on each: the 180 deg arc's rival
// turn hides the reference's bead beyond the scan's edge, and only the scan's bead crest (0.5 % of the 3000 probe
// points, z 3.9) tells them apart; ranked ambiguous until ties were counted again on 12 000 points
// (MultiStartOptions::separation_recount_points).
TEST(CoarseHypothesesMatrix, TubeArcsOverNoiseSamplingAndArc) {
  Mesh reference_mesh;
  reference_mesh.vertices = beaded_tube(0.0, 360.0, 3.0, true);
  const IcpReference reference(reference_mesh);
  struct Case {
    double arc_deg, step_mm, noise_mm;
  };
  const Case cases[] = {{120.0, 1.5, 0.1}, {120.0, 3.0, 0.03}, {90.0, 1.5, 0.03}, {180.0, 2.0, 0.03}};
  Tally t;
  for (std::size_t k = 0; k < std::size(cases); ++k) {
    const Case& c = cases[k];
    Random random(static_cast<std::uint64_t>(710 + k));
    const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 100.0, Eigen::Vector3d::Zero());
    const std::vector<Eigen::Vector3d> scan = test::transformed_points(
        with_noise(beaded_tube(0.0, c.arc_deg, c.step_mm, false), c.noise_mm, random), truth.inverse());
    const CoarseResult r = coarse_align(scan, reference, fpfh_options(700.0, static_cast<std::uint64_t>(k + 1)));
    const Eigen::Vector3d centre = test::mean_point(scan);
    const bool right = test::rotation_error_deg(r.T_ref_scan, truth) < 1.0 &&
                       (r.T_ref_scan * centre - truth * centre).norm() < 1.0;
    const bool passed_on = accepted(r, 1.0);
    std::printf("tube arc %.0f deg, %.1f mm, noise %.2f: %s, %s\n", c.arc_deg, c.step_mm, c.noise_mm,
                right ? "right" : "WRONG", passed_on ? "passed on" : "ambiguous or short");
    t.right += right && passed_on;
    t.refused += !passed_on;
    t.wrong_accepted += !right && passed_on;
  }
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_EQ(t.right, 4);
}

}  // namespace
}  // namespace conform
