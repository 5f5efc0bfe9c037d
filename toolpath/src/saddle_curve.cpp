#include "conform/toolpath/saddle_curve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

// 5-point Gauss-Legendre nodes and weights on [-1, 1]: exact for polynomials of degree 9.
constexpr std::array<double, 5> kNodes = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                          0.9061798459386640};
constexpr std::array<double, 5> kWeights = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                            0.4786286704993665, 0.2369268850561891};
// Widest azimuth span one 5-point rule covers; |dP/dphi| is analytic, so this is at machine precision.
constexpr double kMaxPanelRad = 0.05;

}  // namespace

bool SaddleGeometry::IsValid(std::string* error) const {
  std::ostringstream why;
  const double R = leg_radius_mm;
  const double r = pipe_radius_mm;
  if (!std::isfinite(R) || !std::isfinite(r) || !std::isfinite(pitch_rad) || !std::isfinite(offset_mm)) {
    why << "the cylinder radius R, pipe radius r, pitch and offset must be finite numbers";
  } else if (!(R > 0.0)) {
    why << "the cylinder radius R = " << R << " mm must be positive";
  } else if (!(r > 0.0)) {
    why << "the pipe radius r = " << r << " mm must be positive";
  } else if (!(r < R)) {
    why << "the pipe radius r = " << r << " mm must be smaller than the cylinder radius R = " << R << " mm";
  } else if (!(pitch_rad > 0.0 && pitch_rad <= kHalfPi)) {
    why << "the pitch " << pitch_rad * 90.0 / kHalfPi << " deg is outside (0, 90] deg";
  } else if (!(std::abs(offset_mm) + r < R)) {
    why << "the offset " << offset_mm << " mm is too large: |offset| + r = " << std::abs(offset_mm) + r
        << " mm must be smaller than R = " << R << " mm, or the pipe does not meet the cylinder all the way round";
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
}

// A pipe point (a, b, h) of P is (b cos + h sin, offset + a, b sin - h cos) in L (joint_frames.h); the cylinder
// x_L^2 + y_L^2 = R^2 on the near side (x_L > 0) gives h. At pitch pi/2, offset 0 this is Eq. 7.
Eigen::Vector3d SaddleCurve::point(double phi) const {
  const double r = geometry_.pipe_radius_mm;
  const double R = geometry_.leg_radius_mm;
  const double a = r * std::sin(phi);
  const double b = r * std::cos(phi);
  const double y_leg = geometry_.offset_mm + a;
  const double x_leg = std::sqrt(R * R - y_leg * y_leg);
  return {a, b, (x_leg - b * cos_pitch_) / sin_pitch_};
}

Eigen::Vector3d SaddleCurve::derivative(double phi) const {
  const double r = geometry_.pipe_radius_mm;
  const double R = geometry_.leg_radius_mm;
  const double a = r * std::sin(phi);
  const double b = r * std::cos(phi);
  const double y_leg = geometry_.offset_mm + a;
  const double x_leg = std::sqrt(R * R - y_leg * y_leg);
  // d(a, b)/dphi = (b, -a); d x_leg/dphi = -y_leg b / x_leg.
  return {b, -a, (-y_leg * b / x_leg + a * cos_pitch_) / sin_pitch_};
}

Eigen::Vector3d SaddleCurve::pipe_normal(double phi) const { return {std::sin(phi), std::cos(phi), 0.0}; }

// The cylinder's outward normal (x_L, y_L, 0) / R expressed in P: (y_L, x_L cos, x_L sin) / R.
Eigen::Vector3d SaddleCurve::leg_normal(double phi) const {
  const double R = geometry_.leg_radius_mm;
  const double y_leg = geometry_.offset_mm + geometry_.pipe_radius_mm * std::sin(phi);
  const double x_leg = std::sqrt(R * R - y_leg * y_leg);
  return Eigen::Vector3d(y_leg, x_leg * cos_pitch_, x_leg * sin_pitch_).normalized();
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
// is its angle with the pipe axis z_P.
double SaddleCurve::sin_alpha(double phi) const {
  const Eigen::Vector3d tangent = pipe_normal(phi).cross(leg_normal(phi));
  return tangent.head<2>().norm() / tangent.norm();
}

double SaddleCurve::arc_length(double phi0, double phi1) const {
  const double span = phi1 - phi0;
  if (!(span > 0.0)) return 0.0;
  const int panels = std::max(1, static_cast<int>(std::ceil(span / kMaxPanelRad)));
  const double half = 0.5 * span / panels;
  double sum = 0.0;
  for (int k = 0; k < panels; ++k) {
    const double mid = phi0 + (2 * k + 1) * half;
    for (std::size_t j = 0; j < kNodes.size(); ++j) sum += kWeights[j] * derivative(mid + half * kNodes[j]).norm();
  }
  return sum * half;
}

double SaddleCurve::pipe_residual(const Eigen::Vector3d& p_P) const {
  return std::abs(std::hypot(p_P.x(), p_P.y()) - geometry_.pipe_radius_mm);
}

double SaddleCurve::leg_residual(const Eigen::Vector3d& p_P) const {
  const Eigen::Vector3d p_L = T_L_P_ * p_P;
  return std::abs(std::hypot(p_L.x(), p_L.y()) - geometry_.leg_radius_mm);
}

}  // namespace conform
