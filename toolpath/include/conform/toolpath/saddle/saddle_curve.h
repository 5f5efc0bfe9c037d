#pragma once
// The saddle-shaped weld seam: where a pipe (radius r) meets a cylinder (radius R), in closed form.
// Xue et al. (2018), "Interpolation Algorithm and Mathematical Model in Automated Welding of Saddle-Shaped Weld",
// generalised to any pitch and offset of the pipe (the frames of joint_frames.h). Every quantity is a function of the
// pipe azimuth phi (the paper's rotation angle theta), in the paper frame P:
//
//   P(phi) = (r sin phi, r cos phi, h(phi)),  h = (sqrt(R^2 - (delta + r sin phi)^2) - r cos phi cos(pitch)) /
//   sin(pitch)
//
// which is the paper's x = r sin theta, y = r cos theta (Eq. 1-3) and z = sqrt(R^2 - r^2 sin^2 theta) (Eq. 7) at
// pitch pi/2 and offset 0. Derivation in docs/saddle.md.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/toolpath/intersection/joint_frames.h"

namespace conform {

struct SaddleGeometry {
  double leg_radius_mm = 600.0;           // R, the cylinder the pipe stands on, mm (the paper's example: 600)
  double pipe_radius_mm = 150.0;          // r, the pipe, mm, 0 < r <= R (the paper's example: 150)
  double pitch_rad = 1.5707963267948966;  // angle between the two axes, rad, [1 deg, pi/2]; pi/2 is the paper's case
  double offset_mm = 0.0;                 // distance between the two axes, mm, |offset| + r <= R; 0 is the paper's
  // At |offset| + r = R (r = R, offset 0: an equal-diameter joint) the pipe touches the cylinder tangentially at
  // phi = pi/2 (offset >= 0) and 3 pi/2 (offset <= 0): the seam has a corner there (SaddleCurve::corners()).

  // True when the pipe meets the cylinder all the way round in one closed seam; otherwise says why in *error.
  bool IsValid(std::string* error) const;
  // The same joint as a tube-joint spec (protrusion 0), for T_L_P.
  TubeJointSpec joint() const;
};

class SaddleCurve {
 public:
  // Throws conform::Error with the reason when the geometry is not valid.
  explicit SaddleCurve(const SaddleGeometry& geometry);

  const SaddleGeometry& geometry() const { return geometry_; }

  // Seam point in P, mm (Eq. 1-3 and 7, generalised).
  Eigen::Vector3d point(double phi) const;
  // dP/dphi, mm/rad.
  Eigen::Vector3d derivative(double phi) const;
  // Outward unit normals of the pipe and of the cylinder at the seam point, in P.
  Eigen::Vector3d pipe_normal(double phi) const;
  Eigen::Vector3d leg_normal(double phi) const;
  // Dihedral angle beta between the two surfaces: the angle between their outward normals, rad.
  // At pitch pi/2 and offset 0, cos beta = x^2 / (R r) (Eq. 10-11).
  double dihedral(double phi) const;
  // Torch pose angle pi/2 - beta + start_pose (Eq. 12).
  double pose(double phi, double start_pose_rad) const;
  // sin of the angle alpha between the seam's tangent line (the intersection of the two tangent planes) and the pipe
  // axis (Eq. 19-23). The seam advances r dphi around the pipe per ds = r dphi / sin(alpha) along itself.
  double sin_alpha(double phi) const;
  // Arc length of the seam between two azimuths (phi1 >= phi0), mm: adaptive Gauss-Legendre quadrature of |dP/dphi|
  // split at pi/2 and 3 pi/2, relative tolerance 1e-11 (measured error 1e-13) up to |offset| + r = R. *converged (if given) false when a
  // piece did not meet it.
  double arc_length(double phi0, double phi1, bool* converged = nullptr) const;
  // Azimuths in [0, 2 pi] where the seam has a corner (the pipe touches the cylinder: |offset| + r = R); at a corner
  // derivative() and everything computed from it take the limit from below.
  std::vector<double> corners() const;

  // Distance of a point given in P from the pipe's surface and from the cylinder's surface, mm.
  double pipe_residual(const Eigen::Vector3d& p_P) const;
  double leg_residual(const Eigen::Vector3d& p_P) const;

 private:
  struct LegPoint {
    double y = 0.0;         // y_leg = offset + r sin phi
    double x = 0.0;         // x_leg = sqrt(R^2 - y_leg^2)
    double b_over_x = 0.0;  // r cos phi / x_leg, its limit from below at a corner
  };
  LegPoint leg_point(double phi) const;

  SaddleGeometry geometry_;
  double cos_pitch_ = 0.0;
  double sin_pitch_ = 1.0;
  double gap_plus_ = 0.0;   // R - r - offset >= 0
  double gap_minus_ = 0.0;  // R - r + offset >= 0
  Eigen::Isometry3d T_L_P_ = Eigen::Isometry3d::Identity();
};

}  // namespace conform
