#pragma once
// Shared by the cylinder tests: a generated tube scan (datasets/tube.h) placed far from the origin and tilted, its
// PCA normals, the fit, and the errors against the generator's truth.

#include <cmath>
#include <cstdio>
#include <string>

#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/core/normals.h"
#include "conform/datasets/tube.h"
#include "conform/fitting/cylinder.h"

namespace conform::test {

constexpr double kDeg = kPi / 180.0;

// 50k points on the generator's default tube (R 150 mm, 300 mm long), posed away from the origin on a tilted axis.
inline TubeOptions tube_scan_options(double arc_deg, double noise_mm, std::uint64_t seed = 11) {
  TubeOptions o;
  o.arc_rad = arc_deg * kDeg;
  o.arc_center_rad = 0.7;
  o.noise_mm = noise_mm;
  o.vertex_count = 50000;
  o.seed = seed;
  o.T_world_tube = tube_frame({820.0, -240.0, 515.0}, {0.3, -0.5, 1.0}, {1.0, 0.0, 0.0});
  return o;
}

struct CylinderErrors {
  double radius_mm = 0.0;  // fitted - reference (signed)
  double angle_deg = 0.0;  // between the axes
  double offset_mm =
      0.0;  // the larger of: truth axis point from the fitted axis, fitted axis point from the truth axis
};

inline double distance_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& point, const Eigen::Vector3d& dir) {
  return (p - point).cross(dir.normalized()).norm();
}

inline CylinderErrors errors(const CylinderFitResult& fit, const TubeTruth& truth, double reference_radius_mm) {
  CylinderErrors e;
  e.radius_mm = fit.cylinder.radius_mm - reference_radius_mm;
  const double c = std::abs(fit.cylinder.axis_direction.dot(truth.axis_direction));
  e.angle_deg = std::acos(std::min(1.0, c)) / kDeg;
  e.offset_mm = std::max(distance_to_line(truth.axis_point, fit.cylinder.axis_point, fit.cylinder.axis_direction),
                         distance_to_line(fit.cylinder.axis_point, truth.axis_point, truth.axis_direction));
  return e;
}

struct FittedScan {
  TubeScan scan;
  CylinderFitResult fit;
  CylinderErrors error;
};

// Generates the scan, estimates PCA normals (k = 16, oriented by the faces) and fits.
inline FittedScan fit_generated(const TubeOptions& tube, const CylinderFitOptions& options = {}) {
  FittedScan out;
  out.scan = generate_tube(tube);
  const std::vector<Eigen::Vector3d> normals = estimate_normals(out.scan.mesh, 16);
  out.fit = fit_cylinder(out.scan.mesh.vertices, normals, options);
  out.error = errors(out.fit, out.scan.truth, out.scan.truth.radius_mm);
  return out;
}

inline void print_figures(const char* name, const FittedScan& f) {
  std::printf(
      "[figures] %-34s |dr| %.5f mm  angle %.6f deg  offset %.5f mm  | r_std %.5f  angle_std %.6f deg  rms %.4f  "
      "sigma %.4f  inliers %.4f  ransac %d  rounds %d  lm %d  %s\n",
      name, std::abs(f.error.radius_mm), f.error.angle_deg, f.error.offset_mm, f.fit.radius_std_mm,
      f.fit.axis_angle_std_rad / kDeg, f.fit.rms_mm, f.fit.noise_sigma_mm, f.fit.inlier_fraction,
      f.fit.ransac_iterations, f.fit.refine_rounds, f.fit.solver_iterations, f.fit.termination.c_str());
}

}  // namespace conform::test
