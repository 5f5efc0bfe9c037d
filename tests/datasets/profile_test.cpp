#include "conform/datasets/profile.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

ProfileScanOptions small_case() {
  ProfileScanOptions o;
  o.deformation.length_mm = 3000.0;
  o.deformation.kink_at_mm = 1200.0;
  o.spacing_mm = 5.0;
  o.noise_mm = 0.1;
  o.dropout_fraction = 0.1;
  o.holes = 3;
  o.second_edge = true;
  o.marking_line = true;
  o.seed = 21;
  return o;
}

TEST(ProfileScan, SamplesTheEdgeWithNoiseAndDropouts) {
  const ProfileScanOptions o = small_case();
  const ProfileScan scan = generate_profile_scan(o);
  const ProfileDeformation shape(o.deformation);
  EXPECT_EQ(scan.edge.size() + scan.dropped, 601u);                   // s = 0, 5, ..., 3000
  EXPECT_NEAR(static_cast<double>(scan.dropped) / 599.0, 0.1, 0.04);  // binomial, 599 draws: sd 0.012
  EXPECT_EQ(scan.second_edge.size(), scan.edge.size());
  // The first and last samples are never dropped: the ends are measured.
  EXPECT_LT((scan.edge.front() - shape.edge(0.0)).norm(), 0.6);
  EXPECT_LT((scan.edge.back() - shape.edge(3000.0)).norm(), 0.6);
  // Noise: the mean squared distance from the true edge point is 3 sigma^2 (600 points: RMS within 10 %).
  double sum = 0.0;
  std::size_t j = 0;
  for (const Eigen::Vector3d& p : scan.edge) {
    // The sample's s: the nearest multiple of 5 mm along the (nearly x-aligned) edge.
    double s = 5.0 * std::round(p.x() / 5.0);
    sum += (p - shape.edge(s)).squaredNorm();
    ++j;
  }
  EXPECT_NEAR(std::sqrt(sum / (3.0 * static_cast<double>(j))), 0.1, 0.01);
  // The second edge lies a web width away.
  EXPECT_NEAR((scan.second_edge.front() - scan.edge.front()).norm(), 370.0, 1.0);
}

TEST(ProfileScan, FeaturesAndTheirTruth) {
  const ProfileScanOptions o = small_case();
  const ProfileScan scan = generate_profile_scan(o);
  const ProfileDeformation shape(o.deformation);
  ASSERT_EQ(scan.features.size(), 6u);  // 3 holes + a 3-vertex marking line
  EXPECT_EQ(scan.features[1].id, "H2");
  EXPECT_EQ(scan.features[1].type, "circle");
  EXPECT_DOUBLE_EQ(scan.features[1].ty_mm, 1500.0);  // 3000 (1 + 1/2) / 3
  EXPECT_DOUBLE_EQ(scan.features[1].tx_mm, 100.0);
  EXPECT_DOUBLE_EQ(scan.features[1].radius_mm, 50.0);
  EXPECT_EQ(scan.features[3].type, "polyline");
  ASSERT_EQ(scan.truth.size(), 6u);
  EXPECT_EQ(scan.truth[0].i, -1);
  EXPECT_EQ(scan.truth[5].i, 2);
  for (const ProfileTruthRow& t : scan.truth) {
    EXPECT_LT((t.position - shape.map(t.tx_mm, t.ty_mm)).norm(), 1e-12);
  }
}

TEST(ProfileScan, SameSeedSameNumbers) {
  const ProfileScan a = generate_profile_scan(small_case());
  const ProfileScan b = generate_profile_scan(small_case());
  ASSERT_EQ(a.edge.size(), b.edge.size());
  for (std::size_t i = 0; i < a.edge.size(); ++i) EXPECT_EQ(a.edge[i], b.edge[i]);
  ProfileScanOptions other = small_case();
  other.seed = 22;
  EXPECT_NE(generate_profile_scan(other).edge[1], a.edge[1]);
  // Turning the dropouts off leaves the noise of the kept points alone (independent streams).
  ProfileScanOptions all = small_case();
  all.dropout_fraction = 0.0;
  const ProfileScan full = generate_profile_scan(all);
  ASSERT_EQ(full.edge.size(), 601u);
  for (const Eigen::Vector3d& p : a.edge) {
    EXPECT_EQ(full.edge[static_cast<std::size_t>(std::lround(p.x() / 5.0))], p);  // x is s to within 0.5 mm here
  }
}

TEST(ProfileScan, OutliersOffsetAndReversedListing) {
  ProfileScanOptions o;
  o.deformation.length_mm = 2000.0;
  o.noise_mm = 0.0;
  o.holes = 1;
  const ProfileScan plain = generate_profile_scan(o);
  o.outliers = 3;
  o.outlier_mm = 30.0;
  o.offset_mm = Eigen::Vector3d(1e8, -2e8, 3e6);
  const ProfileScan faulty = generate_profile_scan(o);
  ASSERT_EQ(faulty.edge.size(), plain.edge.size());
  ASSERT_EQ(faulty.outlier_indices.size(), 3u);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < plain.edge.size(); ++i) {
    const double d = (faulty.edge[i] - o.offset_mm - plain.edge[i]).norm();
    const bool listed =
        std::find(faulty.outlier_indices.begin(), faulty.outlier_indices.end(), i) != faulty.outlier_indices.end();
    EXPECT_NEAR(d, listed ? 30.0 : 0.0, 1e-6) << i;  // exactly 30 mm across or along the normal, the rest offset only
    moved += listed ? 1 : 0;
  }
  EXPECT_EQ(moved, 3u);
  EXPECT_NE(faulty.outlier_indices.front(), 0u);
  EXPECT_NE(faulty.outlier_indices.back(), plain.edge.size() - 1);
  EXPECT_LT((faulty.truth[0].position - o.offset_mm - plain.truth[0].position).norm(), 1e-6);
  o.reversed = true;
  const ProfileScan reversed = generate_profile_scan(o);
  EXPECT_EQ(reversed.edge.front(), faulty.edge.back());
  EXPECT_EQ(reversed.edge.back(), faulty.edge.front());
  EXPECT_EQ(reversed.outlier_indices.front(), plain.edge.size() - 1 - faulty.outlier_indices.back());
  EXPECT_EQ(reversed.truth[0].position, faulty.truth[0].position);  // the truth stays in design coordinates
}

TEST(ProfileScan, RejectsBadOptions) {
  ProfileScanOptions o = small_case();
  o.spacing_mm = 0.0;
  EXPECT_THROW(generate_profile_scan(o), Error);
  o = small_case();
  o.hole_radius_mm = 600.0;  // 3 holes of 1.2 m on 3 m overlap
  EXPECT_THROW(generate_profile_scan(o), Error);
  o = small_case();
  o.dropout_fraction = 0.9;
  EXPECT_FALSE(o.IsValid(nullptr));
}

}  // namespace
}  // namespace conform
