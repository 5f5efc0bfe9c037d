#pragma once
// The exact deformed tube surface of a TubeOptions (formula in tube_options.h), evaluated at (theta, z):
// what the generator places its vertices on, and what tests compare a mesh against.

#include <Eigen/Core>

#include "conform/datasets/tube_options.h"

namespace conform {

struct TubeSurfacePoint {
  Eigen::Vector3d point;   // on the deformed surface, mm
  Eigen::Vector3d normal;  // unit; away from the axis for TubeSurface::kOuter, towards it for kInner
  double radius_mm = 0.0;  // r(theta, z): distance from the bowed axis, in the cross-section z = const
};

// The radius function r(theta, z) = R + ovality + seam + bumps (bow not included: it moves the cross-section).
double tube_radius(const TubeOptions& options, double theta_rad, double z_mm);
// The bow's displacement of the cross-section at z, in the tube frame (zero z component).
Eigen::Vector3d tube_bow_offset(const TubeOptions& options, double z_mm);

// Point and normal in the tube frame.
TubeSurfacePoint tube_surface_in_tube(const TubeOptions& options, double theta_rad, double z_mm);
// Point and normal in the world frame (through options.T_world_tube).
TubeSurfacePoint tube_surface(const TubeOptions& options, double theta_rad, double z_mm);

// An angle wrapped into [-pi, pi).
double wrap_angle(double angle_rad);

}  // namespace conform
