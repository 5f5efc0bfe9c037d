#pragma once
// Generalized ICP (Segal, Haehnel & Thrun 2009, "Generalized-ICP"): the plane-to-plane residual's pieces. Each point
// is a sample of a locally planar surface, with covariance C = I - (1 - eps) n n^T (a disc: 1 in the tangent plane,
// eps along the normal n; Sec. III-B), so only the normals are needed.

#include <vector>

#include <Eigen/Core>

namespace conform::detail {

// Unit PCA normals of the points over their k nearest neighbours (their sign is arbitrary: C uses n n^T only).
std::vector<Eigen::Vector3d> plane_normals(const std::vector<Eigen::Vector3d>& points, int k);

// The weight of a pair's difference d = T a - b in Eq. (2): (C_ref + R C_scan R^T)^-1, with n_ref the reference
// point's normal and n_scan the scan point's, already rotated into the reference frame (either may be zero: no
// surface known there, an isotropic covariance).
Eigen::Matrix3d plane_to_plane_information(const Eigen::Vector3d& n_ref, const Eigen::Vector3d& n_scan, double epsilon);

}  // namespace conform::detail
