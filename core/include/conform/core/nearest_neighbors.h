#pragma once
// Nearest-neighbour search over a fixed set of 3D points: k nearest and all within a radius.
// The tree keeps its own copy of the points (float, mm); queries are thread-safe.

#include <cstddef>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace conform {

class KdTree {
 public:
  explicit KdTree(const pcl::PointCloud<pcl::PointXYZ>& points);
  explicit KdTree(const std::vector<Eigen::Vector3d>& points);
  ~KdTree();
  KdTree(KdTree&&) noexcept;
  KdTree& operator=(KdTree&&) noexcept;

  std::size_t size() const;

  // The min(k, size()) nearest points, closest first; squared distances in mm^2.
  void knn(const Eigen::Vector3f& query, int k, std::vector<int>& indices, std::vector<float>& sq_distances) const;
  // All points within `radius` mm (inclusive), closest first.
  void radius(const Eigen::Vector3f& query, float radius, std::vector<int>& indices,
              std::vector<float>& sq_distances) const;
  // Index of the nearest point (-1 when the tree is empty); its squared distance in *sq_distance if given.
  int nearest(const Eigen::Vector3f& query, float* sq_distance = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace conform
