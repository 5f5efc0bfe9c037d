// The S-ICP path checks (compensation/sicp_checks.h) on hand-made registrations with known answers: the correction
// split along a straight path, the noise estimate and outlier segments, blind segments and rows far from the contour.

#include "conform/compensation/sicp_checks.h"

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/random.h"
#include "conform/registration/surface_noise.h"

namespace conform {
namespace {

// A straight open contour along x, 400 mm, points 1 mm apart; the trajectory on it, tool axis +z, rows 1 mm apart.
struct Line {
  Polyline contour;
  Trajectory nominal;
  SicpResult registration;
};

Line line(std::size_t segments_rms_bad = 0) {
  Line l;
  for (int i = 0; i <= 400; ++i) l.contour.points.emplace_back(i, 0.0, 0.0);
  for (int i = 0; i <= 400; ++i) {
    l.nominal.points.emplace_back(i, 0.0, 0.0);
    l.nominal.normals.push_back(Eigen::Vector3d::UnitZ());
  }
  ContourSegmentationOptions o;
  o.segment_length_mm = 40.0;
  l.registration.segmentation = segment_contour(l.contour, o);
  l.registration.converged = true;
  l.registration.segments.resize(l.registration.segmentation.segments.size());
  for (std::size_t k = 0; k < l.registration.segments.size(); ++k) {
    SicpSegmentFit& f = l.registration.segments[k];
    f.usable = true;
    f.neighbourhood_points = 150;
    f.stability_points = 50;
    f.rms_mm = k < segments_rms_bad ? 1.1 : 0.04 + 0.001 * static_cast<double>(k % 3);
  }
  return l;
}

TEST(SicpChecks, CorrectionSplitAcrossAxisAlong) {
  const Line l = line();
  Trajectory moved = l.nominal;
  for (Eigen::Vector3d& p : moved.points) p += Eigen::Vector3d(1.0, 2.0, 3.0);
  const SicpCheck c = check_sicp_path(l.contour, l.registration, l.nominal, moved, SicpCheckOptions{});
  ASSERT_EQ(c.rows.size(), l.nominal.points.size());
  for (const SicpRowReport& r : c.rows) {
    EXPECT_NEAR(r.along_mm, 1.0, 1e-9);   // the path runs along +x
    EXPECT_NEAR(r.across_mm, 2.0, 1e-9);  // z x x = +y, in the surface
    EXPECT_NEAR(r.axis_mm, 3.0, 1e-9);
    EXPECT_NEAR(r.confidence, 1.0, 1e-9);
    EXPECT_NEAR(r.contour_distance_mm, 0.0, 1e-6);
  }
  EXPECT_TRUE(c.trusted) << c.reason;
  EXPECT_NEAR(c.noise_mm, 0.041, 0.0011);  // the median of 0.040, 0.041, 0.042
  EXPECT_TRUE(c.warnings.empty());
}

// The case: three segments end at 1.1 mm RMS, the others at 0.04 mm: outliers, their rows untrusted.
TEST(SicpChecks, OutlierSegmentsMakeThePathUntrusted) {
  const Line l = line(3);
  const SicpCheck c = check_sicp_path(l.contour, l.registration, l.nominal, l.nominal, SicpCheckOptions{});
  EXPECT_EQ(c.outlier_segments, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_LT(c.noise_mm, 0.05);
  EXPECT_FALSE(c.trusted);
  EXPECT_GT(c.untrusted_rows, 80u);  // three 40 mm segments' cores, less the blend into the next
  EXPECT_EQ(c.rows.back().confidence, 1.0);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("far worse"), std::string::npos);
}

TEST(SicpChecks, BlindSegmentsAndFarRows) {
  Line l = line();
  l.registration.segments[4].neighbourhood_points = 3;  // the edge unscanned there
  l.registration.segments[4].stability_points = 0;
  Trajectory nominal = l.nominal;
  nominal.points[400].y() = 25.0;  // the last row 25 mm off the contour
  const SicpCheck c = check_sicp_path(l.contour, l.registration, nominal, nominal, SicpCheckOptions{});
  EXPECT_EQ(c.blind_segments, (std::vector<std::size_t>{4}));
  EXPECT_EQ(c.bare_segments, (std::vector<std::size_t>{4}));
  EXPECT_EQ(c.far_rows, 1u);
  EXPECT_EQ(c.rows[180].confidence, 0.0);  // in segment 4's core (160-200 mm)
  EXPECT_FALSE(c.trusted);
  EXPECT_EQ(c.warnings.size(), 3u);
  // Rows guessed from the neighbours accepted on request (min_edge_points 0); the far row still is not.
  SicpCheckOptions o;
  o.min_edge_points = 0;
  const SicpCheck accepted = check_sicp_path(l.contour, l.registration, nominal, nominal, o);
  EXPECT_TRUE(accepted.blind_segments.empty());
  EXPECT_EQ(accepted.untrusted_rows, 1u);
}

TEST(SicpChecks, NotConvergedIsNotTrustedAndBadInputThrows) {
  Line l = line();
  l.registration.converged = false;
  l.registration.termination = "coarse ICP: too_few_correspondences";
  const SicpCheck c = check_sicp_path(l.contour, l.registration, l.nominal, l.nominal, SicpCheckOptions{});
  EXPECT_FALSE(c.trusted);
  EXPECT_NE(c.reason.find("too_few_correspondences"), std::string::npos);
  Trajectory shorter = l.nominal;
  shorter.points.pop_back();
  shorter.normals.pop_back();
  EXPECT_THROW(check_sicp_path(l.contour, l.registration, l.nominal, shorter, SicpCheckOptions{}), Error);
  SicpCheckOptions bad;
  bad.outlier_ratio = 1.0;
  EXPECT_THROW(check_sicp_path(l.contour, l.registration, l.nominal, l.nominal, bad), Error);
}

// Segment 4 (160-200 mm) has no edge scan but its surface (stability) points: its 40 rows are bridged from the
// measured rows 159 and 200 (a 41 mm stretch), trusted at confidence 1 - 41 / (2 x 150).
TEST(SicpChecks, ShortUnscannedStretchIsBridged) {
  Line l = line();
  l.registration.segments[4].neighbourhood_points = 3;
  const SicpCheck c = check_sicp_path(l.contour, l.registration, l.nominal, l.nominal, SicpCheckOptions{});
  EXPECT_EQ(c.blind_segments, (std::vector<std::size_t>{4}));
  EXPECT_TRUE(c.bare_segments.empty());
  EXPECT_EQ(c.unmeasured_rows, 40u);
  EXPECT_EQ(c.bridged_rows, 40u);
  EXPECT_NEAR(c.longest_gap_mm, 41.0, 1e-9);
  EXPECT_NEAR(c.rows[180].gap_mm, 41.0, 1e-9);
  EXPECT_NEAR(c.rows[180].confidence, 1.0 - 41.0 / 300.0, 1e-9);
  EXPECT_EQ(c.rows[100].gap_mm, 0.0);
  EXPECT_TRUE(c.trusted) << c.reason;
  // Four unscanned segments (160 mm, 161 mm between measured rows) are more than the 150 mm bridged.
  for (std::size_t k : {3u, 5u, 6u}) l.registration.segments[k].neighbourhood_points = 0;
  const SicpCheck far = check_sicp_path(l.contour, l.registration, l.nominal, l.nominal, SicpCheckOptions{});
  EXPECT_NEAR(far.longest_gap_mm, 161.0, 1e-9);
  EXPECT_EQ(far.bridged_rows, 0u);
  EXPECT_EQ(far.untrusted_rows, 160u);
  EXPECT_FALSE(far.trusted);
  EXPECT_NE(far.reason.find("cannot be bridged"), std::string::npos) << far.reason;
}

// Counted at the rows (count_edge_points): an unscanned stretch of 61 mm is bridged on a straight leg, not across
// the corner of an L (the corner's place is a guess) or ending next to it, nor at an open end.
TEST(SicpChecks, UnscannedCornerOrEndIsNotBridged) {
  Line l;
  for (int i = 0; i <= 200; ++i) l.contour.points.emplace_back(i, 0.0, 0.0);
  for (int i = 1; i <= 200; ++i) l.contour.points.emplace_back(200.0, i, 0.0);
  l.nominal.points = l.contour.points;
  l.nominal.normals.assign(l.nominal.points.size(), Eigen::Vector3d::UnitZ());
  ContourSegmentationOptions so;
  so.segment_length_mm = 40.0;
  l.registration.segmentation = segment_contour(l.contour, so);
  ASSERT_EQ(l.registration.segmentation.corners, (std::vector<int>{200}));
  l.registration.converged = true;
  l.registration.segments.resize(l.registration.segmentation.segments.size());
  for (SicpSegmentFit& f : l.registration.segments) f.usable = true, f.neighbourhood_points = 150, f.rms_mm = 0.04;
  // A scan along the path, one point per mm, except within 30 mm of row `hole`.
  const auto check = [&](int hole) {
    std::vector<Eigen::Vector3d> scan;
    for (std::size_t i = 0; i < l.nominal.points.size(); ++i) {
      if (std::abs(static_cast<int>(i) - hole) > 30) scan.push_back(l.nominal.points[i] + Eigen::Vector3d(0, 0, -1));
    }
    const std::vector<std::size_t> counts = count_edge_points(KdTree(scan), l.nominal, 10.0);
    return check_sicp_path(l.contour, l.registration, l.nominal, l.nominal, SicpCheckOptions{}, 0.04, counts);
  };
  const SicpCheck straight = check(100);
  // Capped counts: the same verdicts from the 20 nearest points.
  std::vector<Eigen::Vector3d> line_scan;
  for (int i = 0; i <= 100; ++i) line_scan.emplace_back(i, 0.0, -1.0);
  const Trajectory at{{Eigen::Vector3d(50, 0, 0), Eigen::Vector3d(5, 0, 0), Eigen::Vector3d(50, 20, 0)}, {}};
  EXPECT_EQ(count_edge_points(KdTree(line_scan), at, 10.0), (std::vector<std::size_t>{19, 15, 0}));
  EXPECT_EQ(count_edge_points(KdTree(line_scan), at, 10.0, 12), (std::vector<std::size_t>{12, 12, 0}));
  EXPECT_EQ(straight.rows[100].edge_points, 0u);
  EXPECT_EQ(straight.rows[60].edge_points, 19u);  // scan points 51..69 within 10 mm (1 mm below the rows)
  EXPECT_GT(straight.unmeasured_rows, 30u);
  EXPECT_EQ(straight.bridged_rows, straight.unmeasured_rows);
  EXPECT_TRUE(straight.trusted) << straight.reason;
  EXPECT_TRUE(check(150).trusted);  // the stretch ends ~19 mm before the corner
  for (int hole : {200, 165, 0}) {  // the corner; a stretch ending within 10 mm of it; the open start
    const SicpCheck c = check(hole);
    EXPECT_GT(c.unmeasured_rows, 30u) << hole;
    EXPECT_EQ(c.bridged_rows, 0u) << hole;
    EXPECT_FALSE(c.trusted) << hole;
  }
}

// A gently curved sheet (radius 2500 mm) with a flank along one edge, Gaussian noise sigma 0.05 mm: the estimate
// is the sigma within 10% (the flank's planes are a minority the median leaves out).
TEST(SicpChecks, ScanNoiseFromPlaneFits) {
  Random random(5, 0);
  std::vector<Eigen::Vector3d> scan;
  for (int i = 0; i < 20000; ++i) {
    const double x = random.uniform(0.0, 200.0), y = random.uniform(0.0, 40.0);
    scan.emplace_back(x, y, x * x / 5000.0 + 0.05 * random.normal());
  }
  for (int i = 0; i < 2000; ++i) {
    const double x = random.uniform(0.0, 200.0);
    scan.emplace_back(x, 0.05 * random.normal(), x * x / 5000.0 - random.uniform(0.0, 4.0));
  }
  const KdTree tree(scan);
  // sicp's settings (pipelines/src/sicp/sicp_compensate.cpp): 20 neighbours at 400 points.
  EXPECT_NEAR(estimate_surface_noise(scan, tree, SurfaceNoiseOptions{20, 400}), 0.05, 0.005);
  const std::vector<Eigen::Vector3d> two{{0, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(estimate_surface_noise(two, KdTree(two), SurfaceNoiseOptions{20, 400}), 0.0);
}

}  // namespace
}  // namespace conform
