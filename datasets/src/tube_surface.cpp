#include "conform/datasets/tube_surface.h"

#include <cmath>

namespace conform {

namespace {

// r(theta, z) and its partial derivatives, which give the exact normal.
struct RadiusJet {
  double r = 0.0;
  double dr_dtheta = 0.0;
  double dr_dz = 0.0;
};

// Raised cosine h (1 + cos(pi t)) / 2 on |t| < 1, zero outside: C1, since its slope vanishes at t = 0 and |t| = 1.
// Returns the value and writes d/dt.
double raised_cosine(double height, double t, double* slope) {
  if (std::abs(t) >= 1.0) {
    *slope = 0.0;
    return 0.0;
  }
  *slope = -0.5 * height * M_PI * std::sin(M_PI * t);
  return 0.5 * height * (1.0 + std::cos(M_PI * t));
}

void add_ovality(const TubeOptions& o, double theta, RadiusJet& jet) {
  if (o.ovality_mm == 0.0) return;
  const double phase = 2.0 * (theta - o.ovality_azimuth_rad);
  jet.r += o.ovality_mm * std::cos(phase);
  jet.dr_dtheta += -2.0 * o.ovality_mm * std::sin(phase);
}

// The seam ridge's arc distance s = R * delta_theta maps to t = s / (w / 2): the base is w wide in all.
void add_seam(const TubeOptions& o, double theta, RadiusJet& jet) {
  if (o.seam_height_mm == 0.0) return;
  const double half_width = 0.5 * o.seam_width_mm;
  const double t = o.radius_mm * wrap_angle(theta - o.seam_azimuth_rad) / half_width;
  double slope = 0.0;
  jet.r += raised_cosine(o.seam_height_mm, t, &slope);
  jet.dr_dtheta += slope * o.radius_mm / half_width;
}

// A bump's profile depends on the distance d on the unrolled nominal cylinder; t = d / rho.
void add_bump(const TubeOptions& o, const TubeBump& bump, double theta, double z, RadiusJet& jet) {
  const double du = o.radius_mm * wrap_angle(theta - bump.azimuth_rad);
  const double dz = z - bump.z_mm;
  const double d = std::hypot(du, dz);
  if (d >= bump.radius_mm) return;
  double slope = 0.0;
  jet.r += raised_cosine(bump.height_mm, d / bump.radius_mm, &slope);
  if (d > 0.0) {  // at the centre the slope is zero, and so is the gradient
    const double dr_dd = slope / bump.radius_mm;
    jet.dr_dtheta += dr_dd * du * o.radius_mm / d;
    jet.dr_dz += dr_dd * dz / d;
  }
}

RadiusJet radius_jet(const TubeOptions& o, double theta, double z) {
  RadiusJet jet;
  jet.r = o.radius_mm;
  add_ovality(o, theta, jet);
  add_seam(o, theta, jet);
  for (const TubeBump& bump : o.bumps) add_bump(o, bump, theta, z, jet);
  return jet;
}

Eigen::Vector3d bow_direction(const TubeOptions& o) {
  return {std::cos(o.bow_azimuth_rad), std::sin(o.bow_azimuth_rad), 0.0};
}

}  // namespace

double wrap_angle(double angle_rad) {
  const double two_pi = 2.0 * M_PI;
  return angle_rad - two_pi * std::floor((angle_rad + M_PI) / two_pi);
}

double tube_radius(const TubeOptions& options, double theta_rad, double z_mm) {
  return radius_jet(options, theta_rad, z_mm).r;
}

Eigen::Vector3d tube_bow_offset(const TubeOptions& options, double z_mm) {
  if (options.bow_mm == 0.0) return Eigen::Vector3d::Zero();
  const double u = 2.0 * z_mm / options.length_mm;
  return options.bow_mm * (1.0 - u * u) * bow_direction(options);
}

TubeSurfacePoint tube_surface_in_tube(const TubeOptions& options, double theta_rad, double z_mm) {
  const RadiusJet jet = radius_jet(options, theta_rad, z_mm);
  const double c = std::cos(theta_rad);
  const double s = std::sin(theta_rad);
  const Eigen::Vector3d e_r(c, s, 0.0);
  const Eigen::Vector3d e_theta(-s, c, 0.0);
  const Eigen::Vector3d e_z = Eigen::Vector3d::UnitZ();

  TubeSurfacePoint out;
  out.radius_mm = jet.r;
  out.point = jet.r * e_r + z_mm * e_z + tube_bow_offset(options, z_mm);
  // Normal = S_theta x S_z; with S = r e_r + z e_z + bow(z) d: S_theta = r_theta e_r + r e_theta and
  // S_z = r_z e_r + e_z + bow'(z) d, bow'(z) = -8 s z / L^2. For the round tube it is e_theta x e_z = e_r (outwards).
  const double bow_slope = -8.0 * options.bow_mm * z_mm / (options.length_mm * options.length_mm);
  const Eigen::Vector3d s_theta = jet.dr_dtheta * e_r + jet.r * e_theta;
  const Eigen::Vector3d s_z = jet.dr_dz * e_r + e_z + bow_slope * bow_direction(options);
  out.normal = s_theta.cross(s_z).normalized();
  if (options.surface == TubeSurface::kInner) out.normal = -out.normal;
  return out;
}

TubeSurfacePoint tube_surface(const TubeOptions& options, double theta_rad, double z_mm) {
  TubeSurfacePoint p = tube_surface_in_tube(options, theta_rad, z_mm);
  p.point = options.T_world_tube * p.point;
  p.normal = options.T_world_tube.linear() * p.normal;
  return p;
}

}  // namespace conform
