// RANSAC over correspondences (feature_ransac.h) against a generated truth: random points, a random motion, a share
// of the correspondences right (with noise) and the rest pointing anywhere.

#include <gtest/gtest.h>
#include <omp.h>

#include <utility>
#include <vector>

#include "conform/core/error.h"
#include "conform/core/random.h"
#include "conform/registration/feature_ransac.h"
#include "registration_test_util.h"

namespace conform {
namespace {

struct Problem {
  std::vector<Eigen::Vector3d> scan, reference;
  std::vector<std::pair<int, int>> matches;
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
};

// `n` scan points in a 100 mm cube far from the origin (shop coordinates), the reference their image under a random
// motion with 0.05 mm noise; a share `right` of the correspondences are the true pairs, the rest random.
Problem make_problem(std::uint64_t seed, int n, double right) {
  Random random(seed);
  Problem p;
  p.truth = test::random_motion(random, M_PI, 500.0, Eigen::Vector3d::Zero());
  const Eigen::Vector3d far(5000.0, -3000.0, 800.0);
  for (int i = 0; i < n; ++i) {
    p.scan.push_back(far + Eigen::Vector3d(random.uniform(0, 100), random.uniform(0, 100), random.uniform(0, 100)));
    p.reference.push_back(p.truth * p.scan.back() +
                          0.05 * Eigen::Vector3d(random.normal(), random.normal(), random.normal()));
  }
  for (int i = 0; i < n; ++i) {
    const bool good = random.uniform() < right;
    p.matches.emplace_back(i, good ? i : static_cast<int>(random.below(static_cast<std::uint64_t>(n))));
  }
  return p;
}

FeatureRansacOptions options_for_test() {
  FeatureRansacOptions o;
  o.inlier_distance_mm = 1.0;
  o.seed = 3;
  return o;
}

TEST(FeatureRansac, FindsTheMotionAmongWrongMatches) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Problem p = make_problem(seed, 400, 0.15);
    const FeatureRansacResult r = feature_ransac(p.scan, p.reference, p.matches, options_for_test());
    ASSERT_FALSE(r.poses.empty());
    // Three noisy pairs (0.05 mm on ~50 mm edges) give the pose to a few hundredths of a degree; the best of many
    // samples is scored within 1 mm.
    EXPECT_LT(test::rotation_error_deg(r.poses.front().T_ref_scan, p.truth), 0.5) << "seed " << seed;
    const Eigen::Vector3d c = test::mean_point(p.scan);
    EXPECT_LT((r.poses.front().T_ref_scan * c - p.truth * c).norm(), 0.5) << "seed " << seed;
    EXPECT_GT(r.poses.front().inlier_share, 0.95);
    EXPECT_NEAR(r.match_share, 0.15, 0.06);  // the right correspondences, found
    EXPECT_TRUE(r.stopped_early);            // w = 0.15 needs ~2000 samples for 0.999
    EXPECT_LT(r.iterations, 20000);
    for (std::size_t k = 1; k < r.poses.size(); ++k) {
      EXPECT_LE(r.poses[k].inliers, r.poses[k - 1].inliers);
    }
  }
}

TEST(FeatureRansac, SameResultForAnyNumberOfThreads) {
  const Problem p = make_problem(4, 300, 0.1);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const FeatureRansacResult one = feature_ransac(p.scan, p.reference, p.matches, options_for_test());
  omp_set_num_threads(3);
  const FeatureRansacResult three = feature_ransac(p.scan, p.reference, p.matches, options_for_test());
  omp_set_num_threads(threads);
  ASSERT_EQ(one.poses.size(), three.poses.size());
  EXPECT_EQ(one.iterations, three.iterations);
  EXPECT_EQ(one.scored, three.scored);
  for (std::size_t k = 0; k < one.poses.size(); ++k) {
    EXPECT_TRUE(one.poses[k].T_ref_scan.isApprox(three.poses[k].T_ref_scan, 0.0));
    EXPECT_EQ(one.poses[k].inliers, three.poses[k].inliers);
  }
}

TEST(FeatureRansac, NoRightMatchesFindsNoGoodPose) {
  Problem p = make_problem(5, 200, 0.0);
  FeatureRansacOptions o = options_for_test();
  o.max_iterations = 5000;
  const FeatureRansacResult r = feature_ransac(p.scan, p.reference, p.matches, o);
  EXPECT_EQ(r.iterations, 5000);
  EXPECT_FALSE(r.stopped_early);
  for (const RansacPose& pose : r.poses) EXPECT_LT(pose.inlier_share, 0.2);
}

TEST(FeatureRansac, RejectsBadInput) {
  const Problem p = make_problem(6, 50, 0.5);
  FeatureRansacOptions o = options_for_test();
  EXPECT_THROW(feature_ransac(p.scan, p.reference, {{0, 0}, {1, 1}}, o), Error);
  EXPECT_THROW(feature_ransac(p.scan, p.reference, {{0, 0}, {1, 1}, {2, 50}}, o), Error);
  o.similarity = 1.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THROW(feature_ransac(p.scan, p.reference, p.matches, o), Error);
}

}  // namespace
}  // namespace conform
