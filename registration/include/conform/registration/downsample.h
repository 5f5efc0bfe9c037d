#pragma once
// Fewer points, same surface: one point per occupied voxel (the centroid of the points in it), ordered by voxel, so
// that the same input gives the same output; and an even stride.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace conform {

class KdTree;

// Voxels of voxel_mm (> 0) aligned to the origin. Throws conform::Error for a voxel that is not > 0 or so small that
// voxel indices overflow.
std::vector<Eigen::Vector3d> voxel_downsample(const std::vector<Eigen::Vector3d>& points, double voxel_mm);

// At most `count` points, taken at even steps through the list (all when there are fewer).
std::vector<Eigen::Vector3d> stride_downsample(const std::vector<Eigen::Vector3d>& points, std::size_t count);

// The point spacing: the median over `samples` evenly strided points of the distance to their nearest other point,
// `tree` built over `points`; 0 for fewer than 2 points.
double median_spacing(const std::vector<Eigen::Vector3d>& points, const KdTree& tree, std::size_t samples = 500);

}  // namespace conform
