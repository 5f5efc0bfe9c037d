#pragma once
// Nearest-neighbour search over a fixed set of 3D points: k nearest and all within a radius.
// The tree keeps its own copy of the points (float, mm); queries are thread-safe. A kd-tree (nanoflann; chosen over
// PCL's KdTreeFLANN by bench/nearest_neighbors_bench.cpp). Results are exact and deterministic: squared distances are
// computed in float as dx*dx + dy*dy + dz*dz, and neighbours are ordered by (squared distance, index), so ties go to
// the lower index and the answer equals a brute-force sort.
// Errors (conform::Error): a non-finite input point (callers clean clouds first), a non-finite query, k <= 0, a
// negative or NaN radius. An empty tree is allowed: its queries find nothing.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <Eigen/Core>

namespace conform {

class KdTree {
 public:
  explicit KdTree(const pcl::PointCloud<pcl::PointXYZ>& points);
  explicit KdTree(const std::vector<Eigen::Vector3d>& points);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  std::size_t size() const;

  // The min(k, size()) nearest points, closest first; squared distances in mm^2. The vectors are resized to fit
  // (reusing them across queries avoids allocation).
  void knn(const Eigen::Vector3f& query, int k, std::vector<int>& indices, std::vector<float>& sq_distances) const;
  // All points within `radius` mm, inclusive (squared distance <= radius * radius, in float), closest first.
  void radius(const Eigen::Vector3f& query, float radius, std::vector<int>& indices,
              std::vector<float>& sq_distances) const;
  // Index of the nearest point (-1 when the tree is empty); its squared distance in *sq_distance if given
  // (infinity when the tree is empty).
  int nearest(const Eigen::Vector3f& query, float* sq_distance = nullptr) const;

  // The tree stores its points in the order of its leaves, so that points near in space are near in memory. A
  // position is an index into that order: leaf_order()[position] is the caller's index of the point stored there.
  // The searches by position find the same neighbours in the same order as those above (ties to the lower index
  // of the caller's), named by position: a caller that keeps its own per-point data in leaf order reads what
  // consecutive nearby queries find from nearby memory.
  const std::vector<std::uint32_t>& leaf_order() const;
  Eigen::Vector3f point_at_position(std::size_t position) const;  // position < size()
  void knn_positions(const Eigen::Vector3f& query, int k, std::vector<int>& positions,
                     std::vector<float>& sq_distances) const;
  int nearest_position(const Eigen::Vector3f& query, float* sq_distance = nullptr) const;

 private:
  template <bool kPositions>
  void knn_as(const Eigen::Vector3f& query, int k, std::vector<int>& indices, std::vector<float>& sq_distances) const;
  template <bool kPositions>
  int nearest_as(const Eigen::Vector3f& query, float* sq_distance) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace conform
