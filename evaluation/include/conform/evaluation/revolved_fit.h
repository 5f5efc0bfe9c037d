#pragma once
// Least-squares cones and tori (issue 33): the surface of revolution minimising the sum of squared orthogonal
// distances to the points (ISO 1101's conicity and the form of a torus are zones about such a surface), by
// Levenberg-Marquardt from a nominal start (the CAD face's parameters: a scan in the part frame is close to them).
// Computed relative to the points' centroid, in double. evaluation/form.h has the plane and the sphere.

#include <vector>

#include <Eigen/Core>

namespace conform {

struct ConeFit {
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();  // on the axis: the start's axis point nearest the centroid
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       // unit, from the apex into the cone (the start's sense)
  double radius_mm = 0.0;       // the cone's radius in the plane through axis_point perpendicular to the axis
  double half_angle_rad = 0.0;  // in (0, pi/2)
  Eigen::Vector3d apex = Eigen::Vector3d::Zero();  // axis_point - radius / tan(half_angle) * axis
  double rms_mm = 0.0;          // RMS of the orthogonal distances
  int iterations = 0;
  bool ok = false;  // at least 7 points, converged, the normal equations well conditioned, the angle in (0, pi/2)
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
