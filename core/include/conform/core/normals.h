#pragma once
// Surface normals by principal component analysis: the eigenvector of the smallest eigenvalue of the covariance of
// each point's k nearest neighbours (accumulated in double, centred), oriented consistently.

#include <string>

#include <Eigen/Core>

#include "conform/core/cloud.h"
#include "conform/core/mesh.h"

namespace conform {

enum class NormalOrientation {
  kTowardsViewpoint,  // n . (viewpoint - p) >= 0 (a scanner's position)
  kAwayFromAxis,      // n . (p - its projection on the axis) >= 0 (the outer surface of a tube)
  kTowardsAxis,       // the inner surface of a tube
};

struct NormalOptions {
  int k = 16;                                                   // neighbours per point, >= 3
  NormalOrientation orientation = NormalOrientation::kTowardsViewpoint;
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();         // mm
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();        // mm, for the axis orientations
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();   // any length > 0

  bool IsValid(std::string* error) const;
};

// Unit normals of every point; curvature holds the surface variation l0 / (l0 + l1 + l2).
// Throws conform::Error when options are invalid or the cloud has fewer than 3 points.
pcl::PointCloud<pcl::Normal> estimate_normals(const Cloud& cloud, const NormalOptions& options);

// PCA normals of a mesh's vertices over their k nearest vertices, each oriented to agree with the
// area-weighted normal of the faces around that vertex.
std::vector<Eigen::Vector3d> estimate_normals(const Mesh& mesh, int k = 16);

}  // namespace conform
