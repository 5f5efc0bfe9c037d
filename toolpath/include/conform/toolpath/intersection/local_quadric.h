#pragma once
// A surface patch fitted to a mesh's vertices near a point: the PCA plane of the points, then a quadratic height
// field h(x, y) = a x^2 + b xy + c y^2 + d x + e y + f over it (least squares). Exact to second order, so a tube's
// normal and position come out right even when p is not the neighbourhood's centroid (the plain PCA normal belongs
// to the centroid). Used for the normals n_s, n_l and to refine seam points onto both scanned surfaces.

#include <vector>

#include <Eigen/Core>

namespace conform {

struct LocalQuadric {
  bool quadric = false;  // false: too few or degenerate points, the patch is the PCA plane
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d u = Eigen::Vector3d::UnitX();  // largest principal direction
  Eigen::Vector3d v = Eigen::Vector3d::UnitY();
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();  // smallest: the plane's normal (sign arbitrary)
  double scale = 1.0;                            // coordinates are divided by it for conditioning, mm
  double c[6] = {0, 0, 0, 0, 0, 0};              // a, b, c, d, e, f in scaled coordinates
  double normal_sigma_rad = 0.0;                 // 1-sigma error of the normal at the origin from the residuals
                                                 // (least-squares covariance of the slopes d, e; quadric only)

  // Signed height of p above the patch along n, mm (0 on the surface).
  double height(const Eigen::Vector3d& p) const;
  // Gradient of height(): the (unnormalised) surface normal at the foot of p, pointing along +n.
  Eigen::Vector3d gradient(const Eigen::Vector3d& p) const;
};

// The fit around origin (>= 6 points for the quadric; 3 to 5 give the plane). Throws conform::Error with < 3 points.
LocalQuadric fit_local_quadric(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                               bool quadric = true);

}  // namespace conform
