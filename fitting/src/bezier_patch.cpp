#include "conform/fitting/bezier_patch.h"

#include <Eigen/LU>

namespace conform {
namespace {

// The k-th derivative of a cubic Bézier curve with control points p at t: 3!/(3-k)! times the degree 3-k curve of
// the k-th forward differences (Farin, 5.3), evaluated by de Casteljau.
Eigen::Vector3d cubic_derivative(const Eigen::Vector3d p[4], double t, int k) {
  if (k > 3) return Eigen::Vector3d::Zero();
  Eigen::Vector3d d[4] = {p[0], p[1], p[2], p[3]};
  int n = 3;
  double scale = 1.0;
  for (int order = 0; order < k; ++order) {
    for (int i = 0; i < n; ++i) d[i] = d[i + 1] - d[i];
    scale *= n;
    --n;
  }
  for (int level = n; level > 0; --level) {
    for (int i = 0; i < level; ++i) d[i] = (1.0 - t) * d[i] + t * d[i + 1];
  }
  return scale * d[0];
}

}  // namespace

void split_cubic(const Eigen::Vector3d in[4], double t, Eigen::Vector3d left[4], Eigen::Vector3d right[4]) {
  const Eigen::Vector3d a = (1.0 - t) * in[0] + t * in[1];
  const Eigen::Vector3d b = (1.0 - t) * in[1] + t * in[2];
  const Eigen::Vector3d c = (1.0 - t) * in[2] + t * in[3];
  const Eigen::Vector3d ab = (1.0 - t) * a + t * b;
  const Eigen::Vector3d bc = (1.0 - t) * b + t * c;
  const Eigen::Vector3d m = (1.0 - t) * ab + t * bc;
  left[0] = in[0], left[1] = a, left[2] = ab, left[3] = m;
  right[0] = m, right[1] = bc, right[2] = c, right[3] = in[3];
}

Eigen::Vector3d BezierPatch::position(double u, double v) const { return derivative(u, v, 0, 0); }

Eigen::Vector3d BezierPatch::derivative(double u, double v, int du, int dv) const {
  Eigen::Vector3d column[4];
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d row[4] = {control(i, 0), control(i, 1), control(i, 2), control(i, 3)};
    column[i] = cubic_derivative(row, v, dv);
  }
  return cubic_derivative(column, u, du);
}

std::array<BezierPatch, 4> BezierPatch::subdivide(double u, double v) const {
  // Split every row (fixed i, along v) at v, then every column (fixed j, along u) of both halves at u.
  BezierPatch low_v, high_v;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d row[4] = {control(i, 0), control(i, 1), control(i, 2), control(i, 3)};
    Eigen::Vector3d left[4], right[4];
    split_cubic(row, v, left, right);
    for (int j = 0; j < 4; ++j) low_v.control(i, j) = left[j], high_v.control(i, j) = right[j];
  }
  std::array<BezierPatch, 4> out;
  const BezierPatch* halves[2] = {&low_v, &high_v};
  for (int h = 0; h < 2; ++h) {
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector3d col[4] = {halves[h]->control(0, j), halves[h]->control(1, j), halves[h]->control(2, j),
                                      halves[h]->control(3, j)};
      Eigen::Vector3d left[4], right[4];
      split_cubic(col, u, left, right);
      for (int i = 0; i < 4; ++i) {
        out[static_cast<std::size_t>(2 * h)].control(i, j) = left[i];
        out[static_cast<std::size_t>(2 * h + 1)].control(i, j) = right[i];
      }
    }
  }
  return out;
}

Eigen::AlignedBox3d BezierPatch::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : control_) box.extend(p);
  return box;
}

Eigen::AlignedBox3d BezierPatch::bounds(const Eigen::Matrix3d& R_frame_world) const {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : control_) box.extend(R_frame_world * p);
  return box;
}

BezierPatch interpolating_patch(const std::function<Eigen::Vector3d(double, double)>& f) {
  // Bernstein values at t = k / 3: B[k][i] = B_i(t_k); the patch solves B P B^T = F per coordinate.
  Eigen::Matrix4d B;
  for (int k = 0; k < 4; ++k) {
    const double t = k / 3.0, s = 1.0 - t;
    B.row(k) << s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t;
  }
  const Eigen::Matrix4d B_inv = B.inverse();
  BezierPatch patch;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Matrix4d F;
    for (int k = 0; k < 4; ++k) {
      for (int l = 0; l < 4; ++l) F(k, l) = f(k / 3.0, l / 3.0)[axis];
    }
    const Eigen::Matrix4d P = B_inv * F * B_inv.transpose();
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) patch.control(i, j)[axis] = P(i, j);
    }
  }
  return patch;
}

BezierPatch BezierPatch::transformed(const Eigen::Matrix3d& R, const Eigen::Vector3d& t) const {
  BezierPatch out;
  for (std::size_t k = 0; k < 16; ++k) out.control_[k] = R * control_[k] + t;
  return out;
}

}  // namespace conform
