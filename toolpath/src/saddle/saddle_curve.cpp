#include "conform/toolpath/saddle/saddle_curve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/fitting/arc_length.h"

namespace conform {
namespace {

// Below this pitch the seam stretches by 1 / sin(pitch) > 57: a brace that lies almost along the leg.
constexpr double kMinPitchRad = kPi / 180.0;
// The seam's arc length: relative tolerance of the adaptive quadrature (fitting/arc_length.h). Near a sharp turn the
// speed |dP/dphi| is only as exact as phi itself (its slope times the rounding of phi), and a tighter tolerance
// bisects that noise to the depth limit; at 1e-11 the quadrature converges up to r/R = 1 - 1e-9 and the length is
// within 1e-13 of an independent long-double reference (tests/toolpath/saddle_limits_test.cpp).
constexpr double kArcRelativeTolerance = 1e-11;

}  // namespace

bool SaddleGeometry::IsValid(std::string* error) const {
  std::ostringstream why;
  const double R = leg_radius_mm;
  const double r = pipe_radius_mm;
  if (!std::isfinite(R) || !std::isfinite(r) || !std::isfinite(pitch_rad) || !std::isfinite(offset_mm)) {
    why << "the cylinder radius R, pipe radius r, pitch and offset must be finite numbers";
  } else if (!(R > 0.0)) {
    why << "the cylinder radius R = " << R << " mm must be positive";
  } else if (R > kMaxRadiusMm) {
    why << "the cylinder radius R = " << R << " mm is beyond " << kMaxRadiusMm << " mm (1 km): not a part";
  } else if (!(r > 0.0)) {
    why << "the pipe radius r = " << r << " mm must be positive";
  } else if (!(r <= R)) {
    why << "the pipe radius r = " << r << " mm must not be larger than the cylinder radius R = " << R << " mm";
  } else if (!(pitch_rad >= kMinPitchRad && pitch_rad <= kHalfPi)) {
    why << "the pitch " << pitch_rad * 90.0 / kHalfPi << " deg is outside [1, 90] deg";
  } else if (!((R - r) - std::abs(offset_mm) >= 0.0)) {
    why << "the offset " << offset_mm << " mm is too large: |offset| + r = " << std::abs(offset_mm) + r
        << " mm must not exceed R = " << R << " mm, or the pipe does not meet the cylinder all the way round";
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

TubeJointSpec SaddleGeometry::joint() const {
  TubeJointSpec spec;
  spec.pitch_rad = pitch_rad;
  spec.offset_mm = offset_mm;
  return spec;
}

SaddleCurve::SaddleCurve(const SaddleGeometry& geometry) : geometry_(geometry) {
  std::string error;
  if (!geometry.IsValid(&error)) throw Error("saddle: " + error);
  const Eigen::Vector2d cs = pitch_cos_sin(geometry.pitch_rad);
  cos_pitch_ = cs.x();
  sin_pitch_ = cs.y();
  T_L_P_ = T_L_P(geometry.joint());
  // One rounding each, from the inputs; exactly 0 at a corner (|offset| + r = R).
  gap_plus_ = std::max(0.0, (geometry.leg_radius_mm - geometry.pipe_radius_mm) - geometry.offset_mm);
  gap_minus_ = std::max(0.0, (geometry.leg_radius_mm - geometry.pipe_radius_mm) + geometry.offset_mm);
}

// Where the seam point of azimuth phi lies on the cylinder, in L (joint_frames.h): y_leg = offset + r sin phi and
// x_leg = sqrt(R^2 - y_leg^2) > 0 (the near side). As |offset| + r -> R, R^2 - y_leg^2 cancels to nothing at
// phi = pi/2 or 3 pi/2, so it is formed as (R - y_leg)(R + y_leg) with
//   R - y_leg = (R - offset - r) + 2 r sin^2(pi/4 - phi/2),  R + y_leg = (R + offset - r) + 2 r cos^2(pi/4 - phi/2)
// (1 -+ sin phi = 2 sin^2, 2 cos^2 of pi/4 - phi/2), both sums of non-negative terms: accurate to a few rounding
// units all the way to the limit. b / x_leg (b = r cos phi = 2 r sin cos of pi/4 - phi/2) is formed the same way, so
// that it keeps its one-sided limit at a corner (x_leg = 0 when |offset| + r = R): the limit from below phi.
SaddleCurve::LegPoint SaddleCurve::leg_point(double phi) const {
  const double r = geometry_.pipe_radius_mm;
  const double u = 0.25 * kPi - 0.5 * phi;
  const double su = std::sin(u);
  const double cu = std::cos(u);
  const double below = gap_plus_ + 2.0 * r * su * su;   // R - y_leg
  const double above = gap_minus_ + 2.0 * r * cu * cu;  // R + y_leg
  LegPoint leg;
  leg.y = geometry_.offset_mm + r * std::sin(phi);
  leg.x = std::sqrt(below * above);
  const double b = 2.0 * r * su * cu;
  if (leg.x > 0.0) {
    leg.b_over_x = b / leg.x;
  } else if (below == 0.0) {
    leg.b_over_x = std::copysign(2.0 * r * cu / std::sqrt(2.0 * r * above), su >= 0.0 ? 1.0 : -1.0);
  } else {
    leg.b_over_x = std::copysign(2.0 * r * su / std::sqrt(2.0 * r * below), cu >= 0.0 ? 1.0 : -1.0);
  }
  return leg;
}

// A pipe point (a, b, h) of P is (b cos + h sin, offset + a, b sin - h cos) in L (joint_frames.h); the cylinder
// x_L^2 + y_L^2 = R^2 on the near side (x_L > 0) gives h. At pitch pi/2, offset 0 this is Eq. 7.
Eigen::Vector3d SaddleCurve::point(double phi) const {
  const double r = geometry_.pipe_radius_mm;
  const double b = r * std::cos(phi);
  return {r * std::sin(phi), b, (leg_point(phi).x - b * cos_pitch_) / sin_pitch_};
}

Eigen::Vector3d SaddleCurve::derivative(double phi) const {
  const double r = geometry_.pipe_radius_mm;
  const double a = r * std::sin(phi);
  const double b = r * std::cos(phi);
  const LegPoint leg = leg_point(phi);
  // d(a, b)/dphi = (b, -a); d x_leg/dphi = -y_leg b / x_leg.
  return {b, -a, (-leg.y * leg.b_over_x + a * cos_pitch_) / sin_pitch_};
}

std::vector<double> SaddleCurve::corners() const {
  std::vector<double> out;
  if (gap_plus_ == 0.0) out.push_back(kHalfPi);
  if (gap_minus_ == 0.0) out.push_back(3.0 * kHalfPi);
  return out;
}

Eigen::Vector3d SaddleCurve::pipe_normal(double phi) const { return {std::sin(phi), std::cos(phi), 0.0}; }

// The cylinder's outward normal (x_L, y_L, 0) / R expressed in P: (y_L, x_L cos, x_L sin) / R.
Eigen::Vector3d SaddleCurve::leg_normal(double phi) const {
  const LegPoint leg = leg_point(phi);
  return Eigen::Vector3d(leg.y, leg.x * cos_pitch_, leg.x * sin_pitch_).normalized();
}

// Eq. 10-11 generalised: the angle between the outward normals, by atan2 so that it stays accurate near 0 and pi.
double SaddleCurve::dihedral(double phi) const {
  const Eigen::Vector3d n_pipe = pipe_normal(phi);
  const Eigen::Vector3d n_leg = leg_normal(phi);
  return std::atan2(n_pipe.cross(n_leg).norm(), n_pipe.dot(n_leg));
}

// Eq. 12.
double SaddleCurve::pose(double phi, double start_pose_rad) const { return kHalfPi - dihedral(phi) + start_pose_rad; }

// Eq. 19-23: the seam's tangent line is the intersection of the two tangent planes, direction n_pipe x n_leg; alpha
// is its angle with the pipe axis z_P. That direction is dP/dphi, whose part across the axis is (b, -a), of length r:
// sin(alpha) = r / |dP/dphi|, which stays defined where the two surfaces touch (n_pipe = n_leg at a corner).
double SaddleCurve::sin_alpha(double phi) const { return geometry_.pipe_radius_mm / derivative(phi).norm(); }

// Adaptive Gauss-Legendre (fitting/arc_length.h), split at pi/2 and 3 pi/2: the seam's speed changes fastest there
// as |offset| + r -> R (over an azimuth of about sqrt(2 gap / r)), and has a corner there at the limit; each piece is
// then smooth up to its ends, where the bisection concentrates.
double SaddleCurve::arc_length(double phi0, double phi1, bool* converged) const {
  if (converged != nullptr) *converged = true;
  if (!(phi1 - phi0 > 0.0)) return 0.0;
  std::vector<double> cuts = {phi0};
  for (double k = std::floor(phi0 / kPi - 0.5) + 1.0; k * kPi + kHalfPi < phi1; k += 1.0) {
    cuts.push_back(k * kPi + kHalfPi);
  }
  cuts.push_back(phi1);
  ArcLengthOptions options;
  options.relative_tolerance = kArcRelativeTolerance;
  options.absolute_tolerance_mm = 1e-15 * geometry_.pipe_radius_mm;
  const SpeedFunction speed = [this](double phi) { return derivative(phi).norm(); };
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const ArcLengthIntegral piece = integrate_arc_length(speed, cuts[i], cuts[i + 1], options);
    if (!piece.converged && converged != nullptr) *converged = false;
    sum += piece.length_mm;
  }
  return sum;
}

double SaddleCurve::pipe_residual(const Eigen::Vector3d& p_P) const {
  return std::abs(std::hypot(p_P.x(), p_P.y()) - geometry_.pipe_radius_mm);
}

double SaddleCurve::leg_residual(const Eigen::Vector3d& p_P) const {
  const Eigen::Vector3d p_L = T_L_P_ * p_P;
  return std::abs(std::hypot(p_L.x(), p_L.y()) - geometry_.leg_radius_mm);
}

}  // namespace conform
