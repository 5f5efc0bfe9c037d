#pragma once
// Cutting and welding tool paths from the path frames (Lind & Ystgaard 2020, Sec. 5), in the stub frame S:
//
//   groove angle   alpha(phi), given at the quarters phi = 0 (toe), pi/2 (side), pi (heel), 3 pi/2 (side) and
//                  interpolated cyclically between them (Eq. 5): linearly, or quadratically (C1, flat at the quarters:
//                  alpha_i + (alpha_{i+1} - alpha_i) q(u), q = 2u^2 for u < 1/2, 1 - 2(1 - u)^2 after).
//   cutting        d_c = R(t, alpha_c) t_l_out = cos(alpha_c) t_l_out + sin(alpha_c) n_l   (Eq. 7)
//                  p_c = p - s_c d_c                                                        (Eq. 9)
//                  The torch stands inside the stub, s_c from the seam, cutting outwards along the leg's surface
//                  (alpha_c = 0: the stub end fits the leg square) or tilted away from the leg by the groove angle.
//   welding        t_l_in = -t_l_out;  d_w = R(t, alpha_w) t_l_in = cos(alpha_w) t_l_in - sin(alpha_w) n_l
//                  p_w = p - s_w d_w                                                        (Eq. 11)
//                  The torch stands outside the stub, s_w from the seam, pointing into the groove, lifted off the
//                  leg's surface by alpha_w.
// R(t, a) is the right-handed rotation by a about the seam tangent t (t x t_l_out = n_l).

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/joint_geometry.h"

namespace conform {

enum class GrooveInterpolation { kLinear, kQuadratic };

struct ToolPathOptions {
  std::array<double, 4> groove_rad = {0.0, 0.0, 0.0, 0.0};  // alpha_c at toe, side, heel, side; rad, in (-pi/2, pi/2)
  GrooveInterpolation interpolation = GrooveInterpolation::kLinear;
  double weld_angle_rad = 0.7853981633974483;  // alpha_w, rad, in (-pi/2, pi/2); default 45 deg
  double cut_standoff_mm = 10.0;               // s_c, mm, >= 0
  double weld_standoff_mm = 15.0;              // s_w, mm, >= 0

  bool IsValid(std::string* error) const;
};

// A tool pose: (phi, position, direction), Eq. (10) and (11).
struct ToolPose {
  double phi_rad = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();  // unit
};

struct ToolPaths {
  std::vector<ToolPose> cut;
  std::vector<ToolPose> weld;
  std::vector<double> groove_rad;  // alpha_c used at each point
};

// Eq. (5): the groove angle at azimuth phi (any value; wrapped into [0, 2 pi)).
double groove_angle(const std::array<double, 4>& quarters_rad, GrooveInterpolation interpolation, double phi_rad);

// Rodrigues: v rotated by angle about the unit axis.
Eigen::Vector3d rotate_about(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle_rad);

// Throws conform::Error when the options are invalid.
ToolPaths tool_paths(const std::vector<PathFrame>& frames, const ToolPathOptions& options);

}  // namespace conform
