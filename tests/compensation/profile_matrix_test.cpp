// The realistic-variation matrix of `conform profile` (issue 16): generated scans (datasets/profile.h) with bow, sag
// without bow, twist, kinks, noise 0.02-0.5 mm, sample steps 0.2-20 mm, outliers, gaps, shop-frame offsets and a
// reversed measuring direction, five seeds each. Every case either puts the hole centres within a noise-scaled bound
// of the ground truth, or stops with the message that says what is wrong.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/compensation/profile_compensation.h"
#include "conform/core/error.h"
#include "conform/datasets/profile.h"

namespace conform {
namespace {

constexpr int kSeeds = 5;

ProfileScanOptions paper_case(std::uint64_t seed) {
  ProfileScanOptions o;
  o.deformation.bow_in_plane_mm = 40.0;
  o.deformation.bow_asymmetry = 0.5;
  o.spacing_mm = 5.0;
  o.noise_mm = 0.1;
  o.dropout_fraction = 0.02;
  o.seed = seed;
  return o;
}

std::vector<ProfileFeature> features_of(const ProfileScan& scan) {
  std::vector<ProfileFeature> out;
  for (const ProfileDesignRow& row : scan.features) {
    ProfileFeature f;
    f.id = row.id;
    EXPECT_TRUE(parse_profile_feature_type(row.type, &f.type));
    f.vertices = {{row.tx_mm, row.ty_mm}};
    f.radius_mm = row.radius_mm;
    out.push_back(f);
  }
  return out;
}

double worst_centre_error(const ProfileScan& scan, const ProfileCompensationResult& r) {
  double worst = 0.0;
  for (const ProfileFeatureResult& f : r.features) {
    for (const ProfileTruthRow& t : scan.truth) {
      if (t.id == f.id && t.i == -1) worst = std::max(worst, (f.centre - t.position).norm());
    }
  }
  return worst;
}

// The bound on a hole centre: Ty = 0 is the first measured point, whose own noise along the edge shifts every hole
// (about sigma), plus the fit's error at Tx = 100 mm (a fraction of sigma); 4 sigma + 0.1 mm covers five seeds.
double bound_mm(double sigma) { return 0.1 + 4.0 * sigma; }

struct Case {
  ProfileScanOptions scan;
  ProfileCompensationOptions options;
  bool second_edge = false;
};

// The worst hole error over the seeds; fails the test when one is over the bound.
double run_seeds(Case c, const char* name) {
  double worst = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    c.scan.seed = static_cast<std::uint64_t>(seed);
    const ProfileScan scan = generate_profile_scan(c.scan);
    const ProfileCompensationResult r =
        compensate_profile(scan.edge, features_of(scan), c.options, c.second_edge ? &scan.second_edge : nullptr);
    EXPECT_TRUE(r.ok) << name << " seed " << seed << ": " << r.termination;
    const double error = worst_centre_error(scan, r);
    EXPECT_LT(error, bound_mm(c.scan.noise_mm)) << name << " seed " << seed << " (" << r.edge.selection << ")";
    worst = std::max(worst, error);
  }
  std::printf("[matrix] %-34s worst hole error %.4f mm over %d seeds (bound %.3f)\n", name, worst, kSeeds,
              bound_mm(c.scan.noise_mm));
  return worst;
}

std::string error_of(const ProfileScan& scan, const ProfileCompensationOptions& options, bool second_edge = false) {
  try {
    compensate_profile(scan.edge, features_of(scan), options, second_edge ? &scan.second_edge : nullptr, "edge.csv",
                       "edge2.csv");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ProfileMatrix, BowOverNoiseLevels) {
  for (double sigma : {0.02, 0.1, 0.5}) {
    Case c;
    c.scan = paper_case(1);
    c.scan.noise_mm = sigma;
    const std::string name = "bow 40 mm, sigma " + std::to_string(sigma).substr(0, 4);
    run_seeds(c, name.c_str());
  }
}

TEST(ProfileMatrix, BowOverSampleSteps) {
  for (double step : {0.2, 1.0, 20.0}) {
    Case c;
    c.scan = paper_case(1);
    c.scan.spacing_mm = step;
    c.scan.noise_mm = step < 1.0 ? 0.05 : 0.1;
    if (step < 1.0) c.scan.deformation.length_mm = 4000.0, c.scan.holes = 3;  // 20,000 points a seed
    c.options.edge.points.max_gap_mm = std::max(50.0, 5.0 * step);  // dropouts of a coarse sensor: 5 steps
    const std::string name = "bow 40 mm, step " + std::to_string(step).substr(0, 4) + " mm";
    run_seeds(c, name.c_str());
  }
}

TEST(ProfileMatrix, SagWithoutBowUsesMachineZ) {
  Case c;
  c.scan = paper_case(1);
  c.scan.deformation.bow_in_plane_mm = 0.0;
  c.scan.deformation.bow_out_of_plane_mm = 20.0;
  run_seeds(c, "sag 20 mm, no bow, machine +z");
  // The fitted plane follows the sag, not the web: on request only, and warned about.
  c.scan.seed = 1;
  c.options.fit_web_plane = true;
  const ProfileScan scan = generate_profile_scan(c.scan);
  const ProfileCompensationResult r = compensate_profile(scan.edge, features_of(scan), c.options);
  ASSERT_EQ(r.warnings.size(), 2u);  // the tilt, and the twist one edge cannot see (profile_warnings_test.cpp)
  EXPECT_NE(r.warnings[0].find("tilted"), std::string::npos) << r.warnings[0];
  EXPECT_NE(r.warnings[1].find("twist is not observed"), std::string::npos) << r.warnings[1];
  EXPECT_GT(worst_centre_error(scan, r), 10.0);  // the holes in the air that the default avoids
}

TEST(ProfileMatrix, NearlyStraightEdgeWorksWithMachineZ) {
  Case c;
  c.scan = paper_case(1);
  c.scan.deformation.bow_in_plane_mm = 0.0;
  run_seeds(c, "straight edge, machine +z");
}

TEST(ProfileMatrix, TwistWithTheSecondEdge) {
  Case c;
  c.scan = paper_case(1);
  c.scan.deformation.twist_rad = 0.02;
  c.scan.deformation.bow_out_of_plane_mm = 20.0;
  c.scan.second_edge = true;
  c.second_edge = true;
  run_seeds(c, "twist 1.15 deg + sag 20, second edge");
}

TEST(ProfileMatrix, KinkTakesTheSpline) {
  Case c;
  c.scan = paper_case(1);
  c.scan.deformation.kink_rad = 0.01;
  run_seeds(c, "kink 0.57 deg, auto");
  const ProfileScan scan = generate_profile_scan(c.scan);
  const ProfileCompensationResult r = compensate_profile(scan.edge, features_of(scan), c.options);
  EXPECT_EQ(r.edge.model, ProfileEdgeModel::kSpline) << r.edge.selection;
}

TEST(ProfileMatrix, OutliersAreRejectedAndCounted) {
  for (double size : {3.0, 30.0}) {
    Case c;
    c.scan = paper_case(1);
    c.scan.outliers = 5;
    c.scan.outlier_mm = size;
    const std::string name = "5 outliers of " + std::to_string(size).substr(0, 4) + " mm";
    run_seeds(c, name.c_str());
    for (int seed = 1; seed <= kSeeds; ++seed) {
      c.scan.seed = static_cast<std::uint64_t>(seed);
      const ProfileScan scan = generate_profile_scan(c.scan);
      const ProfileCompensationResult r = compensate_profile(scan.edge, features_of(scan), c.options);
      EXPECT_EQ(r.edge.model, ProfileEdgeModel::kCubic) << "a spike must not flip auto: " << r.edge.selection;
      // Every bad reading found (a few noise points beyond 6 sigma may join them).
      for (std::size_t i : scan.outlier_indices) {
        EXPECT_NE(std::find(r.edge.outlier_indices.begin(), r.edge.outlier_indices.end(), static_cast<int>(i)),
                  r.edge.outlier_indices.end())
            << "seed " << seed << " point " << i;
      }
      EXPECT_LE(r.edge.outliers, scan.outlier_indices.size() + 3);
    }
  }
}

TEST(ProfileMatrix, GapsWithinTheLimitAndBeyond) {
  Case c;
  c.scan = paper_case(1);
  c.scan.dropout_fraction = 0.4;
  run_seeds(c, "40 % dropouts");
  c.scan.dropout_fraction = 0.0;
  c.scan.spacing_mm = 60.0;  // every step a gap beyond the 50 mm limit
  c.scan.noise_mm = 0.1;
  EXPECT_NE(error_of(generate_profile_scan(c.scan), c.options).find("a gap larger than 50 mm"), std::string::npos);
}

TEST(ProfileMatrix, ShopFrameOffsetsGiveTheSameResult) {
  Case c;
  c.scan = paper_case(3);
  c.scan.deformation.kink_rad = 0.01;  // the spline too
  const ProfileScan home = generate_profile_scan(c.scan);
  const ProfileCompensationResult at_home = compensate_profile(home.edge, features_of(home), c.options);
  for (const Eigen::Vector3d& offset : {Eigen::Vector3d(5e7, 0.0, 0.0), Eigen::Vector3d(1e8, -2e8, 3e6)}) {
    c.scan.offset_mm = offset;
    const ProfileScan far = generate_profile_scan(c.scan);
    const ProfileCompensationResult away = compensate_profile(far.edge, features_of(far), c.options);
    ASSERT_EQ(away.features.size(), at_home.features.size());
    EXPECT_EQ(away.edge.model, at_home.edge.model);
    double worst = 0.0;
    for (std::size_t k = 0; k < away.features.size(); ++k) {
      worst = std::max(worst, (away.features[k].centre - offset - at_home.features[k].centre).norm());
      for (std::size_t i = 0; i < away.features[k].mapped.size(); ++i) {
        worst = std::max(worst, (away.features[k].mapped[i] - offset - at_home.features[k].mapped[i]).norm());
      }
    }
    std::printf("[matrix] offset (%.0e, %.0e, %.0e) mm: largest difference from the origin's result %.2e mm\n",
                offset.x(), offset.y(), offset.z(), worst);
    // Coordinates of 2e8 mm carry 3e-8 mm of rounding; the fit itself works in centred coordinates.
    EXPECT_LT(worst, 1e-5);
    EXPECT_LT(worst_centre_error(far, away), bound_mm(c.scan.noise_mm));
  }
}

TEST(ProfileMatrix, ReversedDirection) {
  Case c;
  c.scan = paper_case(1);
  c.scan.reversed = true;
  c.options.reversed = true;
  run_seeds(c, "edge listed from the far end, --direction reverse");
  // Both edges listed from the far end, with the option: the second edge is turned to run beside the first.
  c.scan.second_edge = true;
  c.scan.deformation.twist_rad = 0.02;
  c.second_edge = true;
  run_seeds(c, "both edges reversed, --direction reverse");
  // Without the option, the second edge shows the edge runs the wrong way.
  c.options.reversed = false;
  const std::string message = error_of(generate_profile_scan(c.scan), c.options, true);
  EXPECT_NE(message.find("measured from the profile's far end"), std::string::npos) << message;
}

// Per-feature warnings: what the measurement cannot tell about a feature is said for that feature. A hole over a
// stretch of edge without readings (the readings around a kink removed, --max-gap raised) is warned about, the others
// are not; with one edge every feature off the edge carries the twist it cannot see (Tx sin 1 deg per degree), with
// the second edge none does. The rule: a feature placed farther from its truth than the bound above must carry a
// warning, and a feature without one must be within it.
double centre_error(const ProfileScan& scan, const ProfileFeatureResult& f) {
  for (const ProfileTruthRow& t : scan.truth) {
    if (t.id == f.id && t.i == -1) return (f.centre - t.position).norm();
  }
  ADD_FAILURE() << "no truth for " << f.id;
  return 0.0;
}

bool warned(const ProfileFeatureResult& f, const std::string& what) {
  for (const std::string& w : f.warnings) {
    if (w.find(what) != std::string::npos) return true;
  }
  return false;
}

// Every feature off by more than the bound has a warning; the ones without are within it.
void expect_honest(const ProfileScan& scan, const ProfileCompensationResult& r, double noise_mm, const char* name) {
  const double bound = bound_mm(noise_mm);
  for (const ProfileFeatureResult& f : r.features) {
    const double error = centre_error(scan, f);
    std::printf("[warnings] %-26s %s: %.3f mm, %zu warnings\n", name, f.id.c_str(), error, f.warnings.size());
    if (f.warnings.empty()) {
      EXPECT_LT(error, bound) << name << " " << f.id << ": off without a warning";
    }
  }
}

TEST(ProfileWarningsMatrix, FeaturesOverAStretchWithoutReadings) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    ProfileScanOptions o = paper_case(seed);
    o.deformation.kink_rad = 0.02;  // a 1.15 deg bend at the second hole (Ty 3600 of 12000)
    o.deformation.kink_at_mm = 3600.0;
    ProfileScan scan = generate_profile_scan(o);
    // The readings within 150 mm of the kink lost (a 300 mm stretch).
    std::vector<Eigen::Vector3d> kept;
    double along = 0.0;
    for (std::size_t i = 0; i < scan.edge.size(); ++i) {
      if (i > 0) along += (scan.edge[i] - scan.edge[i - 1]).norm();
      if (std::abs(along - 3600.0) > 150.0) kept.push_back(scan.edge[i]);
    }
    ProfileCompensationOptions options;
    options.edge.points.max_gap_mm = 400.0;
    const ProfileCompensationResult r = compensate_profile(kept, features_of(scan), options, nullptr);
    ASSERT_TRUE(r.ok) << r.termination;
    ASSERT_EQ(r.features.size(), 5u);
    for (std::size_t k = 0; k < r.features.size(); ++k) {
      EXPECT_EQ(warned(r.features[k], "without readings"), k == 1) << r.features[k].id;
      EXPECT_EQ(r.features[k].gap_mm > 290.0, k == 1) << r.features[k].gap_mm;
    }
    expect_honest(scan, r, o.noise_mm, "kink in a 300 mm gap");
    // With every reading there, no feature is over a gap.
    const ProfileCompensationResult full = compensate_profile(scan.edge, features_of(scan), options, nullptr);
    for (const ProfileFeatureResult& f : full.features) EXPECT_FALSE(warned(f, "without readings")) << f.id;
  }
}

TEST(ProfileWarningsMatrix, TwistUnobservableWithOneEdge) {
  for (const double twist : {0.0, 0.02, 0.2}) {
    ProfileScanOptions o = paper_case(2);
    o.deformation.twist_rad = twist;
    o.deformation.bow_out_of_plane_mm = 20.0;
    o.second_edge = true;
    const ProfileScan scan = generate_profile_scan(o);
    const ProfileCompensationResult one = compensate_profile(scan.edge, features_of(scan), {}, nullptr);
    ASSERT_TRUE(one.ok) << one.termination;
    for (const ProfileFeatureResult& f : one.features) {
      EXPECT_TRUE(warned(f, "twist is not observed")) << f.id;
      EXPECT_NEAR(f.twist_mm_per_deg, 150.0 * std::sin(3.141592653589793 / 180.0), 1e-9);  // Tx up to 100 + 50 mm
    }
    const std::string name = "twist " + std::to_string(twist).substr(0, 4) + " rad, one edge";
    expect_honest(scan, one, o.noise_mm, name.c_str());
    const ProfileCompensationResult two = compensate_profile(scan.edge, features_of(scan), {}, &scan.second_edge);
    ASSERT_TRUE(two.ok) << two.termination;
    for (const ProfileFeatureResult& f : two.features) EXPECT_FALSE(warned(f, "twist")) << f.id;
    expect_honest(scan, two, o.noise_mm, "second edge");
  }
}

}  // namespace
}  // namespace conform
