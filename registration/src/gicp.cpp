#include "gicp.h"

#include "conform/core/cloud.h"
#include "conform/core/normals.h"

namespace conform::detail {

std::vector<Eigen::Vector3d> plane_normals(const std::vector<Eigen::Vector3d>& points, int k) {
  Cloud cloud;
  cloud.points.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    cloud.points.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  NormalOptions options;
  options.k = k;
  const pcl::PointCloud<pcl::Normal> normals = estimate_normals(cloud, options);
  std::vector<Eigen::Vector3d> out(normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i) out[i] = normals[i].getNormalVector3fMap().cast<double>();
  return out;
}

Eigen::Matrix3d plane_to_plane_information(const Eigen::Vector3d& n_ref, const Eigen::Vector3d& n_scan,
                                           double epsilon) {
  // C_ref + R C_scan R^T, both discs (Sec. III-B): eigenvalues between 2 eps and 2, so the inverse is well defined.
  const Eigen::Matrix3d sum =
      2.0 * Eigen::Matrix3d::Identity() - (1.0 - epsilon) * (n_ref * n_ref.transpose() + n_scan * n_scan.transpose());
  return sum.inverse();
}

}  // namespace conform::detail
