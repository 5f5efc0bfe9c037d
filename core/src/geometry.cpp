#include "conform/core/geometry.h"
#include "conform/core/z_order.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

#include "conform/core/error.h"

namespace conform {

namespace {

// Spreads the low 21 bits of v so that bit b moves to bit 3b (the bit interleaving of a Morton code).
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffffu;
  v = (v | v << 32) & 0x1f00000000ffffu;
  v = (v | v << 16) & 0x1f0000ff0000ffu;
  v = (v | v << 8) & 0x100f00f00f00f00fu;
  v = (v | v << 4) & 0x10c30c30c30c30c3u;
  v = (v | v << 2) & 0x1249249249249249u;
  return v;
}

template <typename Points, typename Get>
BoundingBox box_of(const Points& points, Get get) {
  BoundingBox box;
  for (const auto& p : points) {
    const Eigen::Vector3d q = get(p);
    if (q.allFinite()) box.extend(q);
  }
  return box;
}

template <typename Points, typename Get>
Eigen::Vector3d mean_of(const Points& points, Get get, const char* what) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const auto& p : points) {
    const Eigen::Vector3d q = get(p);
    if (!q.allFinite()) continue;
    sum += q;
    ++n;
  }
  if (n == 0) throw Error(std::string("centroid of ") + what + ": no finite point");
  return sum / static_cast<double>(n);
}

Eigen::Vector3d of_pcl(const pcl::PointXYZ& p) { return p.getVector3fMap().cast<double>(); }
const Eigen::Vector3d& of_eigen(const Eigen::Vector3d& p) { return p; }

}  // namespace

BoundingBox bounding_box(const Cloud& cloud) { return box_of(cloud.points, of_pcl); }
BoundingBox bounding_box(const Mesh& mesh) { return box_of(mesh.vertices, of_eigen); }
BoundingBox bounding_box(const Polyline& polyline) { return box_of(polyline.points, of_eigen); }

Eigen::Vector3d centroid(const Cloud& cloud) { return mean_of(cloud.points, of_pcl, "a cloud"); }
Eigen::Vector3d centroid(const Mesh& mesh) { return mean_of(mesh.vertices, of_eigen, "a mesh"); }
Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& points) { return mean_of(points, of_eigen, "points"); }

double largest_displacement(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& A,
                            const Eigen::Isometry3d& B) {
  double largest = 0.0;
  for (const Eigen::Vector3d& p : points) largest = std::max(largest, (A * p - B * p).norm());
  return largest;
}

std::size_t count_non_finite(const Cloud& cloud) {
  std::size_t n = 0;
  for (const pcl::PointXYZ& p : cloud.points) n += p.getVector3fMap().allFinite() ? 0 : 1;
  return n;
}

std::size_t count_non_finite(const Mesh& mesh) {
  std::size_t n = 0;
  for (const Eigen::Vector3d& p : mesh.vertices) n += p.allFinite() ? 0 : 1;
  return n;
}

Cloud transformed(const Cloud& cloud_a, const Eigen::Isometry3d& T_b_a) {
  Cloud cloud_b = cloud_a;
  const Eigen::Matrix3d R = T_b_a.linear();
  for (pcl::PointXYZ& p : cloud_b.points) {
    p.getVector3fMap() = (T_b_a * p.getVector3fMap().cast<double>()).cast<float>();
  }
  for (pcl::Normal& n : cloud_b.normals) {
    n.getNormalVector3fMap() = (R * n.getNormalVector3fMap().cast<double>()).cast<float>();
  }
  return cloud_b;
}

Mesh transformed(const Mesh& mesh_a, const Eigen::Isometry3d& T_b_a) {
  Mesh mesh_b = mesh_a;
  const Eigen::Matrix3d R = T_b_a.linear();
  for (Eigen::Vector3d& p : mesh_b.vertices) p = T_b_a * p;
  for (Eigen::Vector3d& n : mesh_b.normals) n = R * n;
  return mesh_b;
}

Polyline transformed(const Polyline& polyline_a, const Eigen::Isometry3d& T_b_a) {
  Polyline polyline_b = polyline_a;
  for (Eigen::Vector3d& p : polyline_b.points) p = T_b_a * p;
  return polyline_b;
}

std::vector<std::size_t> z_order(const std::vector<Eigen::Vector3d>& points) {
  const BoundingBox box = box_of(points, [](const Eigen::Vector3d& p) { return p; });
  constexpr double kCells = 2097151.0;  // 2^21 - 1 per axis: three axes fill 63 bits
  // In double, so that the scale of a thin box stays finite; a flat axis (all points equal in it) gets scale 0.
  const Eigen::Array3d size = box.size().array();
  const Eigen::Array3d scale = (size > 0.0).select(kCells / size, 0.0);
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::uint64_t key = std::numeric_limits<std::uint64_t>::max();
    if (points[i].allFinite()) {
      const Eigen::Array3d cell = ((points[i] - box.min).array() * scale).min(kCells).max(0.0);
      key = spread_bits(static_cast<std::uint64_t>(cell.x())) | spread_bits(static_cast<std::uint64_t>(cell.y())) << 1 |
            spread_bits(static_cast<std::uint64_t>(cell.z())) << 2;
    }
    keyed[i] = {key, i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) order[i] = keyed[i].second;
  return order;
}

}  // namespace conform
