#pragma once
// Cutting and welding tool paths from the path frames (Lind & Ystgaard 2020, Sec. 5), in the stub frame S:
//
//   groove angle   alpha(phi), given at the quarters phi = 0 (toe), pi/2 (side), pi (heel), 3 pi/2 (side) or as any
//                  table of (phi, alpha) rows, interpolated cyclically (Eq. 5, groove_table.h).
//   cutting        d_c = R(t, alpha_c) t_l_out = cos(alpha_c) t_l_out + sin(alpha_c) n_l   (Eq. 7)
//                  p_c = p - s_c d_c                                                        (Eq. 9)
//                  The torch stands inside the stub, s_c from the seam, cutting outwards along the leg's surface
//                  (alpha_c = 0: the stub end fits the leg square) or tilted away from the leg by the groove angle.
//   welding        t_l_in = -t_l_out;  d_w = R(t, alpha_w) t_l_in = cos(alpha_w) t_l_in - sin(alpha_w) n_l
//                  p_w = p - s_w d_w                                                        (Eq. 11)
//                  The torch stands outside the stub, s_w from the seam, pointing into the groove, lifted off the
//                  leg's surface by alpha_w.
// R(t, a) is the right-handed rotation by a about the seam tangent t (t x t_l_out = n_l).
//   dihedral       psi, the angle at p in the (n_s, n_l) cross-section from t_l_out to the stub wall's direction away
//                  from the leg (u = +-(t x n_s), u . z_S < 0): the wall's material fills the angles (alpha_c, psi)
//                  after the cut, so a cut needs alpha_c < psi, and a weld torch at alpha_w in (alpha_c, psi) stands
//                  in the stub wall unless s_w sin(psi - alpha_w) exceeds its thickness (tool_safety.h).

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/intersection/groove_table.h"
#include "conform/toolpath/intersection/joint_geometry.h"

namespace conform {

struct ToolPathOptions {
  std::array<double, 4> groove_rad = {0.0, 0.0, 0.0, 0.0};  // alpha_c at toe, side, heel, side; rad, in [0, pi/2)
  // Instead of the quarters, when not empty: (phi_rad, alpha_rad) rows (groove_table.h).
  std::vector<std::pair<double, double>> groove_table_rad;
  GrooveInterpolation interpolation = GrooveInterpolation::kLinear;
  double weld_angle_rad = 0.7853981633974483;  // alpha_w, rad, in [0, pi/2); default 45 deg
  double cut_standoff_mm = 10.0;               // s_c, mm, >= 0
  double weld_standoff_mm = 15.0;              // s_w, mm, >= 0

  bool IsValid(std::string* error) const;
  GrooveTable groove() const;  // the table in use
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
  std::vector<double> psi_rad;     // the dihedral angle at each point (above)
  double weld_angle_rad = 0.0;     // alpha_w
};

// The dihedral angle psi at a path frame (above), rad, in (0, pi) for a seam the stub stands on.
double dihedral_angle(const PathFrame& frame);

// Eq. (5): the groove angle at azimuth phi (any value; wrapped into [0, 2 pi)).
double groove_angle(const std::array<double, 4>& quarters_rad, GrooveInterpolation interpolation, double phi_rad);

// Rodrigues: v rotated by angle about the unit axis.
Eigen::Vector3d rotate_about(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle_rad);

// Throws conform::Error when the options are invalid.
ToolPaths tool_paths(const std::vector<PathFrame>& frames, const ToolPathOptions& options);

}  // namespace conform
