#include "conform/core/geometry.h"

#include <string>

#include "conform/core/error.h"

namespace conform {

namespace {

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

}  // namespace conform
