#pragma once
// Least-squares cones and tori: the surface of revolution minimising the sum of squared orthogonal distances to the
// points (ISO 1101's conicity and the form of a torus are zones about such a surface), from a nominal start (the CAD
// face's parameters: a scan in the part frame is close to them). Solved with Ceres (Levenberg-Marquardt, dense QR,
// analytic derivatives), the axis on the unit sphere (ceres::SphereManifold), in coordinates centred on the points'
// centroid, in double. evaluation/form.h has the plane and the sphere, fitting/cylinder.h the cylinder.
//
// ok says the fit is an answer: enough points, Ceres converged, the parameters in range, and the problem well
// conditioned: the Jacobian at the solution (in the manifold's tangent space), its columns scaled to unit length,
// has a smallest singular value above 1e-6 of its largest (the normal equations' eigenvalues 1e-12 apart at most).

#include <vector>

#include <Eigen/Core>

namespace conform {

struct ConeFit {
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // on the axis, in the plane through the points' centroid
                                                         // across the start's axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       // unit, from the apex into the cone (the start's sense)
  double radius_mm = 0.0;       // the cone's radius in the plane through axis_point perpendicular to the axis
  double half_angle_rad = 0.0;  // in (0, pi/2)
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();  // axis_point - radius / tan(half_angle) * axis
  double rms_mm = 0.0;          // RMS of the orthogonal distances
  int iterations = 0;
  bool ok = false;  // at least 7 points, converged, well conditioned, the angle in (0, pi/2) and the radius > 0
};

// The signed distance of p from the cone (+ away from the axis): (rho - r - h tan a) cos a with h along the axis from
// axis_point and rho the distance from the axis; exact for points nearer the cone than its axis, on the apex's far side.
double cone_distance(const ConeFit& cone, const Eigen::Vector3d& p);

// Start: the apex, the unit axis (into the cone) and the half-angle, rad, of the nominal cone.
ConeFit fit_cone(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& apex, const Eigen::Vector3d& axis,
                 double half_angle_rad);

struct TorusFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // unit, the start's sense
  double major_radius_mm = 0.0;                     // centre to the tube's centre circle
  double minor_radius_mm = 0.0;                     // the tube's
  double rms_mm = 0.0;
  int iterations = 0;
  bool ok = false;  // at least 8 points, converged, well conditioned, both radii > 0
};

// The signed distance of p from the torus (+ away from the tube's centre circle).
double torus_distance(const TorusFit& torus, const Eigen::Vector3d& p);

// Start: the nominal centre, unit axis and radii.
TorusFit fit_torus(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& axis, double major_radius_mm, double minor_radius_mm);

}  // namespace conform
