// Per-feature warnings of `conform profile` on generated scans with ground truth (datasets/profile.h): what the
// measurement cannot tell about a feature is said for that feature. A hole over a stretch of edge without readings
// (the readings around a kink removed, --max-gap raised) is warned about, the others are not; with one edge every
// feature off the edge carries the twist it cannot see (Tx sin 1 deg per degree), with the second edge none does.
// The matrix rule: a feature placed farther from its truth than the noise-scaled bound of the profile matrix must
// carry a warning, and a feature without one must be within that bound.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/compensation/profile_compensation.h"
#include "conform/datasets/profile.h"

namespace conform {
namespace {

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

ProfileScanOptions paper_case(std::uint64_t seed) {
  ProfileScanOptions o;
  o.deformation.bow_in_plane_mm = 40.0;
  o.deformation.bow_asymmetry = 0.5;
  o.noise_mm = 0.1;
  o.seed = seed;
  return o;
}

// Every feature off by more than the bound has a warning; the ones without are within it.
void expect_honest(const ProfileScan& scan, const ProfileCompensationResult& r, double noise_mm, const char* name) {
  const double bound = 0.1 + 4.0 * noise_mm;
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
