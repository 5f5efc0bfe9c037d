#pragma once
// Bounding boxes, centroids and rigid transforms of clouds, meshes and polylines.
// A transform is named after its frames: T_b_a maps coordinates in frame a into frame b (p_b = T_b_a * p_a).

#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/cloud.h"
#include "conform/core/mesh.h"
#include "conform/core/polyline.h"

namespace conform {

// Axis-aligned box over the finite points; empty() when there are none.
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (min.array() > max.array()).any(); }
  void extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  Eigen::Vector3d size() const { return empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(max - min); }
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
  double diagonal() const { return size().norm(); }
};

BoundingBox bounding_box(const Cloud& cloud);
BoundingBox bounding_box(const Mesh& mesh);
BoundingBox bounding_box(const Polyline& polyline);

// Mean of the finite points, accumulated in double. Throws conform::Error when there is no finite point.
Eigen::Vector3d centroid(const Cloud& cloud);
// Mean of the finite vertices (not the area-weighted surface centroid).
Eigen::Vector3d centroid(const Mesh& mesh);
// Mean of the finite points. Throws conform::Error when there is no finite point.
Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& points);

// Points with a NaN or infinite coordinate.
std::size_t count_non_finite(const Cloud& cloud);
std::size_t count_non_finite(const Mesh& mesh);

// Points (and normals, rotated) mapped from frame a to frame b by T_b_a.
Cloud transformed(const Cloud& cloud_a, const Eigen::Isometry3d& T_b_a);
Mesh transformed(const Mesh& mesh_a, const Eigen::Isometry3d& T_b_a);
Polyline transformed(const Polyline& polyline_a, const Eigen::Isometry3d& T_b_a);

// How far two poses of the same points set them apart: the largest |A p - B p| over `points` (0 for none), in the
// points' units. Two fits of one scan compared as the scan sees them, whatever their centres of rotation.
double largest_displacement(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& A,
                            const Eigen::Isometry3d& B);

}  // namespace conform
