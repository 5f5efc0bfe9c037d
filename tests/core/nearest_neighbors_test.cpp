#include "conform/core/nearest_neighbors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

using Cloud3 = pcl::PointCloud<pcl::PointXYZ>;

// The tree's distance, evaluated the same way (float, left to right), so that results compare exactly.
float sq_distance(const Eigen::Vector3f& q, const pcl::PointXYZ& p) {
  const float dx = q.x() - p.x, dy = q.y() - p.y, dz = q.z() - p.z;
  return dx * dx + dy * dy + dz * dz;
}

// All points sorted by (squared distance, index): the reference the tree must reproduce.
using Ranking = std::vector<std::pair<float, int>>;

Ranking brute_force(const Cloud3& cloud, const Eigen::Vector3f& q) {
  Ranking all;
  for (std::size_t i = 0; i < cloud.size(); ++i) all.emplace_back(sq_distance(q, cloud[i]), static_cast<int>(i));
  std::sort(all.begin(), all.end());
  return all;
}

void expect_knn_matches(const KdTree& tree, const Ranking& all, const Eigen::Vector3f& q, int k) {
  std::vector<int> indices;
  std::vector<float> d2;
  tree.knn(q, k, indices, d2);
  const std::size_t expected = std::min(static_cast<std::size_t>(k), all.size());
  ASSERT_EQ(indices.size(), expected);
  ASSERT_EQ(d2.size(), expected);
  for (std::size_t i = 0; i < expected; ++i) {
    ASSERT_EQ(indices[i], all[i].second) << "k = " << k << ", rank " << i << " of " << all.size() << " points";
    ASSERT_EQ(d2[i], all[i].first) << "k = " << k << ", rank " << i;
  }
}

void expect_radius_matches(const KdTree& tree, Ranking all, const Eigen::Vector3f& q, float r) {
  std::vector<int> indices;
  std::vector<float> d2;
  tree.radius(q, r, indices, d2);
  all.erase(std::remove_if(all.begin(), all.end(), [&](const auto& e) { return e.first > r * r; }), all.end());
  ASSERT_EQ(indices.size(), all.size()) << "radius " << r;
  ASSERT_EQ(d2.size(), all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    ASSERT_EQ(indices[i], all[i].second) << "radius " << r << ", rank " << i;
    ASSERT_EQ(d2[i], all[i].first);
  }
}

Cloud3 random_cloud(std::size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  Cloud3 cloud;
  for (std::size_t i = 0; i < n; ++i) cloud.push_back(pcl::PointXYZ(u(rng), u(rng), u(rng)));
  return cloud;
}

// Queries: random points in and around the cloud's box, and points of the cloud itself (distance 0).
std::vector<Eigen::Vector3f> queries_for(const Cloud3& cloud, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-60.0f, 60.0f);
  std::vector<Eigen::Vector3f> queries;
  for (int i = 0; i < 20; ++i) queries.emplace_back(u(rng), u(rng), u(rng));
  for (std::size_t i = 0; i < std::min<std::size_t>(cloud.size(), 10); ++i) {
    queries.push_back(cloud[rng() % cloud.size()].getVector3fMap());
  }
  return queries;
}

TEST(KdTree, KnnEqualsBruteForceOnRandomClouds) {
  std::mt19937 rng(20240611);
  for (std::size_t n : {1u, 2u, 3u, 10u, 57u, 500u, 4000u}) {
    const Cloud3 cloud = random_cloud(n, rng);
    const KdTree tree(cloud);
    ASSERT_EQ(tree.size(), n);
    for (const Eigen::Vector3f& q : queries_for(cloud, rng)) {
      const Ranking all = brute_force(cloud, q);
      for (int k : {1, 2, 5, 16, 50}) expect_knn_matches(tree, all, q, k);
      float d2 = -1.0f;
      const int nearest = tree.nearest(q, &d2);
      EXPECT_EQ(nearest, all[0].second);
      EXPECT_EQ(d2, all[0].first);
    }
  }
}

TEST(KdTree, RadiusEqualsBruteForceOnRandomClouds) {
  std::mt19937 rng(7);
  for (std::size_t n : {1u, 10u, 300u, 4000u}) {
    const Cloud3 cloud = random_cloud(n, rng);
    const KdTree tree(cloud);
    for (const Eigen::Vector3f& q : queries_for(cloud, rng)) {
      const Ranking all = brute_force(cloud, q);
      for (float r : {0.0f, 1.0f, 5.0f, 12.5f, 200.0f}) expect_radius_matches(tree, all, q, r);
    }
  }
}

// Points on a grid, many of them duplicated: exact distance ties everywhere, and points exactly on the radius.
// The larger cloud makes a deeper tree (more incremental cell-distance rounding in nanoflann).
TEST(KdTree, TiesAndDuplicatesResolveToTheLowerIndex) {
  std::mt19937 rng(3);
  for (const auto& [n, steps, step] : {std::tuple{3000, 4, 1.0f}, std::tuple{60000, 40, 0.25f}}) {
    std::uniform_int_distribution<int> coord(-steps, steps);
    const auto grid = [&] { return step * static_cast<float>(coord(rng)); };
    Cloud3 cloud;
    for (int i = 0; i < n; ++i) cloud.push_back(pcl::PointXYZ(grid(), grid(), grid()));
    const KdTree tree(cloud);
    for (int i = 0; i < 40; ++i) {
      const Eigen::Vector3f q(grid() + 0.5f * step * static_cast<float>(rng() % 2), grid(), grid());
      const Ranking all = brute_force(cloud, q);
      for (int k : {1, 3, 8, 30, 200}) expect_knn_matches(tree, all, q, k);
      for (float r : {0.0f, 0.5f, 1.0f, 1.5f, 2.0f, 3.0f}) expect_radius_matches(tree, all, q, r * step);
    }
  }
}

// The searches by storage position find the brute-force neighbours (ties included), named by position: leaf_order()
// is a permutation that maps them back, and point_at_position() holds the point stored there.
TEST(KdTree, PositionSearchesFindTheSameNeighbours) {
  std::mt19937 rng(13);
  for (std::size_t n : {1u, 50u, 3000u}) {
    Cloud3 cloud = random_cloud(n, rng);
    for (std::size_t i = 0; i + 1 < n; i += 7) cloud.push_back(cloud[i]);  // duplicates: ties to the lower index
    const KdTree tree(cloud);
    const std::vector<std::uint32_t>& index_at = tree.leaf_order();
    ASSERT_EQ(index_at.size(), cloud.size());
    std::vector<bool> seen(cloud.size(), false);
    for (std::size_t p = 0; p < index_at.size(); ++p) {
      ASSERT_LT(index_at[p], cloud.size());
      ASSERT_FALSE(seen[index_at[p]]) << "position " << p;
      seen[index_at[p]] = true;
      ASSERT_EQ(tree.point_at_position(p), cloud[index_at[p]].getVector3fMap()) << "position " << p;
    }
    std::vector<int> positions;
    std::vector<float> d2;
    for (const Eigen::Vector3f& q : queries_for(cloud, rng)) {
      const Ranking all = brute_force(cloud, q);
      for (int k : {1, 2, 16}) {
        tree.knn_positions(q, k, positions, d2);
        ASSERT_EQ(positions.size(), std::min<std::size_t>(static_cast<std::size_t>(k), all.size()));
        for (std::size_t r = 0; r < positions.size(); ++r) {
          ASSERT_EQ(static_cast<int>(index_at[static_cast<std::size_t>(positions[r])]), all[r].second) << "k " << k;
          ASSERT_EQ(d2[r], all[r].first);
        }
      }
      float sq = 0.0f;
      const int p = tree.nearest_position(q, &sq);
      ASSERT_EQ(static_cast<int>(index_at[static_cast<std::size_t>(p)]), all[0].second);
      ASSERT_EQ(sq, all[0].first);
    }
  }
  const KdTree empty{Cloud3()};
  EXPECT_TRUE(empty.leaf_order().empty());
  EXPECT_EQ(empty.nearest_position(Eigen::Vector3f::Zero()), -1);
}

TEST(KdTree, KLargerThanTheCloudGivesAllPoints) {
  std::mt19937 rng(11);
  const Cloud3 cloud = random_cloud(25, rng);
  const KdTree tree(cloud);
  const Eigen::Vector3f q(1.0f, 2.0f, 3.0f);
  expect_knn_matches(tree, brute_force(cloud, q), q, 26);
  expect_knn_matches(tree, brute_force(cloud, q), q, 1000);
  std::vector<int> indices;
  std::vector<float> d2;
  tree.knn(q, 1000, indices, d2);
  EXPECT_EQ(indices.size(), 25u);
}

TEST(KdTree, EmptyTreeFindsNothing) {
  const KdTree tree{Cloud3()};
  EXPECT_EQ(tree.size(), 0u);
  std::vector<int> indices{1, 2};
  std::vector<float> d2{1.0f, 2.0f};
  tree.knn(Eigen::Vector3f::Zero(), 5, indices, d2);
  EXPECT_TRUE(indices.empty());
  EXPECT_TRUE(d2.empty());
  indices = {1};
  tree.radius(Eigen::Vector3f::Zero(), 10.0f, indices, d2);
  EXPECT_TRUE(indices.empty());
  float sq = 0.0f;
  EXPECT_EQ(tree.nearest(Eigen::Vector3f::Zero(), &sq), -1);
  EXPECT_EQ(sq, std::numeric_limits<float>::infinity());
  EXPECT_EQ(KdTree(std::vector<Eigen::Vector3d>()).nearest(Eigen::Vector3f::Ones()), -1);
}

TEST(KdTree, Vector3dConstructorGivesTheSameResults) {
  std::mt19937 rng(5);
  const Cloud3 cloud = random_cloud(800, rng);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : cloud) points.push_back(p.getVector3fMap().cast<double>());
  const KdTree from_cloud(cloud);
  const KdTree from_vectors(points);
  ASSERT_EQ(from_vectors.size(), cloud.size());
  std::vector<int> a, b;
  std::vector<float> da, db;
  for (const Eigen::Vector3f& q : queries_for(cloud, rng)) {
    expect_knn_matches(from_vectors, brute_force(cloud, q), q, 12);
    from_cloud.radius(q, 9.0f, a, da);
    from_vectors.radius(q, 9.0f, b, db);
    EXPECT_EQ(a, b);
    EXPECT_EQ(da, db);
  }
}

TEST(KdTree, MovedTreeKeepsWorking) {
  std::mt19937 rng(9);
  const Cloud3 cloud = random_cloud(300, rng);
  KdTree original(cloud);
  KdTree moved(std::move(original));
  const Eigen::Vector3f q(3.0f, -2.0f, 1.0f);
  expect_knn_matches(moved, brute_force(cloud, q), q, 7);
  KdTree assigned{Cloud3()};
  assigned = std::move(moved);
  expect_knn_matches(assigned, brute_force(cloud, q), q, 7);
}

TEST(KdTree, RejectsBadInput) {
  Cloud3 cloud;
  cloud.push_back(pcl::PointXYZ(0.0f, 0.0f, 0.0f));
  cloud.push_back(pcl::PointXYZ(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f));
  cloud.push_back(pcl::PointXYZ(1.0f, std::numeric_limits<float>::infinity(), 0.0f));
  cloud.push_back(pcl::PointXYZ(1.0f, 1.0f, 1.0f));
  try {
    const KdTree tree(cloud);
    FAIL() << "non-finite points were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2 of 4 points are not finite"), std::string::npos) << e.what();
  }
  // A double beyond the float range cannot be stored.
  EXPECT_THROW(KdTree(std::vector<Eigen::Vector3d>{Eigen::Vector3d(1e300, 0.0, 0.0)}), Error);

  cloud.erase(cloud.begin() + 1, cloud.begin() + 3);
  const KdTree tree(cloud);
  std::vector<int> indices;
  std::vector<float> d2;
  EXPECT_THROW(tree.knn(Eigen::Vector3f::Zero(), 0, indices, d2), Error);
  EXPECT_THROW(tree.knn(Eigen::Vector3f::Zero(), -3, indices, d2), Error);
  EXPECT_THROW(tree.radius(Eigen::Vector3f::Zero(), -1.0f, indices, d2), Error);
  EXPECT_THROW(tree.radius(Eigen::Vector3f::Zero(), std::numeric_limits<float>::quiet_NaN(), indices, d2), Error);
  const Eigen::Vector3f nan_query(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  EXPECT_THROW(tree.knn(nan_query, 1, indices, d2), Error);
  EXPECT_THROW(tree.nearest(nan_query), Error);
  // Even an empty tree rejects a bad k.
  EXPECT_THROW(KdTree(Cloud3()).knn(Eigen::Vector3f::Zero(), 0, indices, d2), Error);
}

}  // namespace
}  // namespace conform
