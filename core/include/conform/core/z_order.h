#pragma once
// A spatially coherent order of points, for work done point after point.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace conform {

// The points' indices along a Z-curve (Morton order, 21 bits an axis) over their finite bounding box: points near in
// space come near each other in the order, so that work done point after point (nearest-neighbour searches, the
// reference data they find) stays in cache. Ties keep index order; a non-finite point sorts last. Deterministic.
std::vector<std::size_t> z_order(const std::vector<Eigen::Vector3d>& points);

}  // namespace conform
