#pragma once
// When ICP has converged: when its step is far below what the data resolves. The pose's predicted covariance is
// sigma^2 (N H)^-1 (degeneracy.h: H the normalised point-to-plane normal matrix of the step's N pairs, sigma their
// robust noise), so a step x (a scaled twist about the pairs' centre: rotation x L, translation) has the length,
// in units of the pose's own standard deviation,
//
//   m(x) = sqrt(x^T (sigma^2 (N H)^-1)^-1 x) = sqrt(N x^T H x) / sigma = sqrt(sum_i (J_i x)^2) / sigma,     (1)
//
// the Mahalanobis length of the step: how far (in noise units, summed in quadrature over the pairs) the step moves
// the residuals. A step is converged when
//
//   m(x_k) + t_k <= f    or    the step rotates <= rotation tolerance and moves <= translation tolerance,   (2)
//
// with t_k the motion still to come if the steps shrink geometrically: t_k = m(x_k) rho / (1 - rho), rho =
// m(x_k) / m(x_{k-1}), when the last two steps point the same way (cosine > 0.9 in the metric of (1)); infinite
// when they do not shrink; 0 when they do not point the same way (pairs flipping at the noise level make ICP cycle
// among a few poses a fraction of a std apart: the pose is then known to that fraction, which is what converged
// means). The absolute tolerances are the numerical floor of a noise-free fit (its sigma is the kernel's 1 um floor).

#include <algorithm>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/registration/degeneracy.h"

namespace conform::detail {

// The rigid motion `delta` taken `factor` times over, about `centre`: its rotation angle and its displacement of
// `centre` scaled.
Eigen::Isometry3d scaled_motion(const Eigen::Isometry3d& delta, const Eigen::Vector3d& centre, double factor);

// The scaled twist (rotation vector x L, displacement of `centre`) of a rigid motion, about `centre`.
Vector6d scaled_twist(const Eigen::Isometry3d& delta, const Eigen::Vector3d& centre, double length_scale_mm);

class ConvergenceTest {
 public:
  // fraction: f of (2); tolerances: the absolute floor (rad, mm), both as given times any stage scale.
  ConvergenceTest(double fraction, double rotation_tolerance_rad, double translation_tolerance_mm)
      : fraction_(fraction),
        rotation_tolerance_rad_(rotation_tolerance_rad),
        translation_tolerance_mm_(translation_tolerance_mm) {}

  // The step `delta` (applied on the left of the pose) taken from pairs whose normal matrix is `plane` and noise
  // `noise_mm`: whether (2) holds.
  bool converged(const Eigen::Isometry3d& delta, const PlaneNormalMatrix& plane, double noise_mm);

  double last_std_fraction() const { return last_m_; }  // m(x_k) of (1)
  // The last two steps pointed the same way and the last was the shorter: a motion still under way (a creep), not
  // a cycle among poses.
  bool creeping() const { return creeping_; }
  // When creeping: how many times the last step to take instead, 1 / (1 - rho) (the geometric series' sum), at most
  // `cap`; 1 otherwise. The next converged() then judges the step after the jump with the rate measured before it
  // (the jump shortens that step more than the rate does, which would understate the motion still to come).
  double jump_factor(double cap) const { return creeping_ ? std::min(cap, 1.0 / (1.0 - rho_)) : 1.0; }
  void jumped() { jumped_rho_ = rho_; }

 private:
  double fraction_;
  double rotation_tolerance_rad_;
  double translation_tolerance_mm_;
  bool has_previous_ = false;
  Eigen::Isometry3d previous_ = Eigen::Isometry3d::Identity();
  double last_m_ = 0.0;
  bool creeping_ = false;
  double rho_ = 0.0;          // m(x_k) / m(x_{k-1}) when creeping
  double jumped_rho_ = -1.0;  // the rate at the last jump, until the next step is judged; < 0: none
};

}  // namespace conform::detail
