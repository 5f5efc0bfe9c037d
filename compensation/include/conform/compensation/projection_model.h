#pragma once
// The simple alternative for small, smooth deformations (Béarée et al. 2010, section 2.2): one rigid transform (ICP
// of the contour's neighbourhood), then the deformation left over, measured along the normal of the contour's
// least-squares plane and fitted with a smooth function of the position in that plane: a parabola z = a w^2 along
// the plane's principal direction w (with offset and tilt terms, which a rigid fit leaves near zero), or a
// thin-plate spline. Nominal points map to T p + f(u, v) N.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/polyline.h"
#include "conform/registration/icp_reference.h"

namespace conform {

enum class ProjectionFit {
  kParabola,         // f = c0 + c1 u + c2 v + c3 u^2 (u along the principal direction)
  kThinPlateSpline,  // f = a0 + a1 u + a2 v + sum w_j r_j^2 log r_j over centres on the contour, smoothed
};

const char* to_string(ProjectionFit fit);

struct ProjectionOptions {
  ProjectionFit fit = ProjectionFit::kParabola;
  double neighbourhood_mm = 10.0;  // scan points this close to the contour (after the rigid transform) are samples
  double max_distance_mm = 5.0;    // ... when they lie this close to the nominal surface
  int spline_centres = 40;         // thin-plate spline centres, evenly along the contour, >= 3
  double spline_smoothing = 1e-4;  // ridge on the spline weights, relative to the data's scale, >= 0
  bool IsValid(std::string* error) const;
};

struct ProjectionModel {
  Eigen::Isometry3d T_scan_nominal = Eigen::Isometry3d::Identity();  // the rigid part
  // The plane, in the scan frame: origin, in-plane axes u (principal) and v, normal N.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_axis = Eigen::Vector3d::UnitX(), v_axis = Eigen::Vector3d::UnitY(),
                  normal = Eigen::Vector3d::UnitZ();
  ProjectionFit fit = ProjectionFit::kParabola;
  Eigen::VectorXd coefficients;          // parabola: c0..c3; spline: a0, a1, a2, w_1..w_m
  std::vector<Eigen::Vector2d> centres;  // spline centres (u, v), mm
  std::size_t samples = 0;               // deviations the fit used
  double rms_mm = 0.0;                   // of the fit's residuals

  // f(u, v) and its gradient, mm and mm/mm.
  double height(const Eigen::Vector2d& uv) const;
  Eigen::Vector2d gradient(const Eigen::Vector2d& uv) const;
  // A nominal point and its unit normal on the deformed part.
  Eigen::Vector3d map_point(const Eigen::Vector3d& p_nominal) const;
  Eigen::Vector3d map_normal(const Eigen::Vector3d& p_nominal, const Eigen::Vector3d& n_nominal) const;
};

// scan: points in the scan frame; nominal: the nominal surface (faces: point-to-surface, else point-to-plane).
// Throws conform::Error for invalid options or too few samples (fewer than the fit's unknowns times 3).
ProjectionModel fit_projection_model(const Polyline& contour, const IcpReference& nominal,
                                     const std::vector<Eigen::Vector3d>& scan, const Eigen::Isometry3d& T_scan_nominal,
                                     const ProjectionOptions& options);

}  // namespace conform
