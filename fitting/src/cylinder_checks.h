#pragma once
// The figures that judge a fitted cylinder (private to the fitting module): noise scale, the arc the inliers span,
// which side of the wall the normals show, the alternatives (plane, sphere) and the parameter covariance.

#include <vector>

#include <Eigen/Core>

#include "conform/fitting/cylinder.h"

namespace conform::detail {

// 1.4826 median |v|: the standard deviation of Gaussian values, unmoved by up to half of them being outliers.
// Zero for no values.
double robust_sigma(std::vector<double> values);
double median_abs(std::vector<double> values);

// The scanner's noise sigma as the median over (at most 512, evenly strided) points of the RMS distance of their k
// nearest neighbours from the neighbourhood's PCA plane, corrected for the 3 degrees of freedom the plane takes.
double local_noise_sigma(const std::vector<Eigen::Vector3d>& points, int k);

// Angular span of the points about the axis: 2 pi less the widest empty gap between their azimuths (0.5 deg bins).
double arc_span(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices, const Cylinder& model);

// kOuter (kInner) when at least 90% of the normals point away from (towards) the axis.
CylinderSide wall_side(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                       const std::vector<int>& indices, const Cylinder& model);

// RMS distance of the points from their PCA plane.
double plane_rms(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices);

// Median |residual| of all points to the algebraic least-squares sphere |p|^2 = 2 c.p + k (Kasa's linear circle fit,
// 1976, in 3D); infinity when no real sphere fits.
double sphere_median(const std::vector<Eigen::Vector3d>& points);

struct CylinderCovariance {
  Eigen::Matrix<double, 5, 5> covariance = Eigen::Matrix<double, 5, 5>::Zero();
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  // columns e1, e2, axis
  double radius_std_mm = 0.0;
  double axis_angle_std_rad = 0.0;
  double axis_point_std_mm = 0.0;
};

// sigma^2 (J^T J)^-1 over the inliers at the solution, J the derivatives of the residual by (tilt towards e1, e2;
// axis-point shift along e1, e2; radius): -(z n.e1, z n.e2, n.e1, n.e2, 1) with z the point's height along the axis
// from the axis point and n its unit radial direction.
CylinderCovariance cylinder_covariance(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& inliers,
                                       const Cylinder& model);

}  // namespace conform::detail
