#pragma once
// Interpolation of the saddle-shaped weld seam for a welding machine that turns about the pipe axis (Xue et al. 2018):
// the machine's rotation angle theta at each interpolation step, the torch position and the torch pose angle.
//
//   equal-angle     constant dtheta; the last step is shortened to land exactly on 2 pi (Table 1 of the paper).
//   variable-angle  dtheta = v dT sin(alpha) / r (Eq. 13-24), alpha taken at the step's midpoint theta + dtheta/2, so
//                   that dtheta sits on both sides of Eq. 24; solved by fixed-point iteration at every step. The torch
//                   then moves v dT per period: constant linear speed.
//   arc-length      beyond the paper: dtheta such that the seam's arc length over the step is exactly v dT
//                   (Gauss-Legendre quadrature of |dP/dtheta|, Newton's method). Any pitch and offset.
//
// All three work for any pitch and offset (saddle_curve.h); the paper's case is pitch pi/2, offset 0.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/saddle/saddle_curve.h"

namespace conform {

enum class SaddleStepRule { kEqualAngle, kVariableAngle, kArcLength };

// "equal-angle", "variable-angle", "arc-length".
const char* to_string(SaddleStepRule rule);

struct SaddleOptions {
  SaddleGeometry geometry;  // R, r, pitch, offset; defaults: the paper's R 600, r 150, T joint
  // phi of Eq. 12 (the paper's "starting pose angle"), rad, in (-pi, pi]: the torch pose angle where the two surfaces
  // meet at a right angle (dihedral beta = pi/2); the pose is pi/2 - beta + phi. For the paper's joint beta(0) = pi/2
  // and it is the pose at theta = 0; for a pitched or offset joint the pose at theta = 0 differs. Paper: pi/4.
  double start_pose_rad = 0.7853981633974483;
  SaddleStepRule rule = SaddleStepRule::kEqualAngle;
  double step_rad = 0.15707963267948966;  // equal-angle dtheta, rad, in (0, pi); default pi/20 (Table 1)
  double speed_mm_per_s = 80.0 / 60.0;    // v, torch speed along the seam, mm/s; default 80 mm/min (paper)
  double period_s = 0.004;                // dT, interpolation period, s; default 4 ms
  std::size_t max_points = 10000000;      // refuse inputs that would need more points than this

  // Checks the geometry, the pose angle phi in (-pi, pi], and the values the chosen rule uses: step in (0, pi), or
  // speed and period positive with v dT no larger than r (a longer step cuts across the seam). Says why in *error.
  bool IsValid(std::string* error) const;
};

struct SaddlePoint {
  double theta_rad = 0.0;                              // machine rotation = pipe azimuth, from 0 to 2 pi inclusive
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // seam point in the paper frame P (joint_frames.h), mm
  double pose_rad = 0.0;                               // torch pose angle (Eq. 12), rad
  double step_mm = 0.0;                                // 3D distance from the previous point, mm; 0 for the first
};

struct SaddleResult {
  std::vector<SaddlePoint> points;  // first at theta 0, last at theta 2 pi (the same seam point: a closed path)
  SaddleStepRule rule = SaddleStepRule::kEqualAngle;
  // every per-step equation solved to tolerance, the seam's length integral converged and the path (chords) not longer
  // than the seam
  bool converged = false;
  std::string termination;  // why converged is false, or "ok"
  int max_iterations = 0;   // most solver iterations any step needed (0 for equal-angle)

  // Step figures over the full steps: a last step shortened to land on 2 pi is left out (reported on its own).
  double step_mm_min = 0.0;
  double step_mm_max = 0.0;
  double step_mm_mean = 0.0;
  double speed_ripple_pct = 0.0;   // 100 (max - min) / mean of the full steps' 3D lengths
  double last_step_mm = 0.0;       // the step landing on 2 pi
  bool last_step_partial = false;  // true when that step was shortened
  std::size_t corner_steps = 0;    // steps shortened to end on a corner of the seam (|offset| + r = R)
  std::size_t full_steps = 0;      // steps in the figures above: all but the shortened ones

  double curve_length_mm = 0.0;  // arc length of the seam (quadrature), mm
  double path_length_mm = 0.0;   // sum of the 3D steps (the polyline through the points), mm
  double pose_rad_min = 0.0;
  double pose_rad_max = 0.0;
  double max_pipe_residual_mm = 0.0;  // largest distance of a point from the pipe surface
  double max_leg_residual_mm = 0.0;   // largest distance of a point from the cylinder surface
};

// Throws conform::Error naming the bad value when !options.IsValid().
SaddleResult interpolate_saddle(const SaddleOptions& options);

}  // namespace conform
