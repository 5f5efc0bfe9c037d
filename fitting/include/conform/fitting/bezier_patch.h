#pragma once
// A bicubic tensor-product Bézier patch over [0, 1]^2 (Farin, Curves and Surfaces for CAGD, ch. 16):
//   r(u, v) = sum_i sum_j B_i(u) B_j(v) b_ij,  B_k the cubic Bernstein polynomials,
// control point b_ij at control(i, j), i along u, j along v. Evaluation is de Casteljau's algorithm (rows first,
// then the resulting column), derivatives up to second order come from the differences of the control net, and
// subdivision splits the net exactly (the pieces reproduce the patch). The surface lies in the convex hull of its
// control points, so the axis-aligned box of the control points bounds it: what the intersection relies on.

#include <array>
#include <functional>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

class BezierPatch {
 public:
  BezierPatch() { control_.fill(Eigen::Vector3d::Zero()); }
  // Control points row by row: control_points[4 * i + j] = b_ij.
  explicit BezierPatch(const std::array<Eigen::Vector3d, 16>& control_points) : control_(control_points) {}

  const Eigen::Vector3d& control(int i, int j) const { return control_[static_cast<std::size_t>(4 * i + j)]; }
  Eigen::Vector3d& control(int i, int j) { return control_[static_cast<std::size_t>(4 * i + j)]; }
  const std::array<Eigen::Vector3d, 16>& control_points() const { return control_; }

  // de Casteljau evaluation.
  Eigen::Vector3d position(double u, double v) const;
  // d^(du + dv) r / du^du dv^dv, du, dv in [0, 3].
  Eigen::Vector3d derivative(double u, double v, int du, int dv) const;

  // The four pieces of a split at (u, v) in (0, 1)^2: [0] = [0, u] x [0, v], [1] = [u, 1] x [0, v],
  // [2] = [0, u] x [v, 1], [3] = [u, 1] x [v, 1], each reparametrised over [0, 1]^2.
  std::array<BezierPatch, 4> subdivide(double u = 0.5, double v = 0.5) const;

  // Axis-aligned box of the control points (contains the patch). With `R_frame_world` the box is taken in that
  // rotated frame (p_frame = R_frame_world * p_world): a frame that follows the surface gives tighter boxes.
  Eigen::AlignedBox3d bounds() const;
  Eigen::AlignedBox3d bounds(const Eigen::Matrix3d& R_frame_world) const;

  // The patch with every control point mapped by p -> R * p + t.
  BezierPatch transformed(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) const;

 private:
  std::array<Eigen::Vector3d, 16> control_;
};

// The patch through f(u, v) at the 16 parameters {0, 1/3, 2/3, 1}^2: exact (f reproduced everywhere) when f is a
// polynomial of degree <= 3 in each parameter, such as a plane or a paraboloid over a rectangle.
BezierPatch interpolating_patch(const std::function<Eigen::Vector3d(double, double)>& f);

// The cubic curve's four control points split at t: left = [0, t], right = [t, 1] (de Casteljau's triangle).
void split_cubic(const Eigen::Vector3d in[4], double t, Eigen::Vector3d left[4], Eigen::Vector3d right[4]);

}  // namespace conform
