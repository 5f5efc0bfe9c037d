#pragma once
// One pass over a point-to-plane step's pairs for everything the step needs: the normalised normal matrix
// (degeneracy.h, PlaneNormalMatrix), the weighted Gauss-Newton normal equations and the RMS. The residual moment
// (the sandwich covariance's middle) only matters for the figures reported, so it is taken once, at the end
// (residual_moment_of).
// Before, each was its own pass (the centroid, the spread, the moments, the normal equations, the RMS: five passes
// over 100k pairs a step). The sums are taken about a fixed origin o and moved to the pairs' centroid c and length
// scale L afterwards, exactly: with u = (q - o) x n, the Jacobian about c is
//
//   J_c = [((q - c) x n) / L ; n] = A [u ; n],   A = [[I / L, [o - c]x / L], [0, I]],
//
// so sum s J_c J_c^T = A (sum s K K^T) A^T and sum s J_c = A sum s K, with K = [u ; n].

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <Eigen/Geometry>

#include "block_sum.h"
#include "conform/registration/degeneracy.h"

namespace conform::detail {

struct StepSums {
  PlaneNormalMatrix plane;        // unweighted, without the residual moment
  Matrix6d H = Matrix6d::Zero();  // sum w J J^T (about plane.centre, scaled by plane.length_scale_mm)
  Vector6d g = Vector6d::Zero();  // sum w r J
  double rms_mm = 0.0;            // sqrt(mean r^2)
};

// [a]x: the matrix of the cross product, [a]x b = a x b.
inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return m;
}

namespace step_sums_detail {

// Symmetric 6x6 sums as their 21 upper-triangle entries: half the work of the full products.
using Upper = Eigen::Matrix<double, 21, 1>;

struct Moments {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double sq = 0.0;               // sum |q - o|^2
  double r2 = 0.0;               // sum r^2
  Upper S = Upper::Zero();       // sum K K^T
  Upper down = Upper::Zero();    // sum (1 - w) K K^T: the weighted sum is S - down (most weights are 1)
  Vector6d gw = Vector6d::Zero();  // sum w r K
  Moments& operator+=(const Moments& o) {
    sum += o.sum;
    sq += o.sq;
    r2 += o.r2;
    S += o.S;
    down += o.down;
    gw += o.gw;
    return *this;
  }
};

inline Upper upper_products(const Vector6d& K) {
  Upper u;
  for (int i = 0, t = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j) u(t++) = K(i) * K(j);
  }
  return u;
}

inline Matrix6d symmetric(const Upper& u) {
  Matrix6d m;
  for (int i = 0, t = 0; i < 6; ++i) {
    for (int j = i; j < 6; ++j, ++t) m(i, j) = m(j, i) = u(t);
  }
  return m;
}

}  // namespace step_sums_detail

// item(k, q, n, r, w) for k in [0, n): sets the k-th pair's scan point q (reference frame), reference normal n,
// residual r along it (mm) and robust weight w; `origin`: any point near the pairs (the sums' precision).
template <typename Item>
StepSums step_sums(std::size_t n, const Eigen::Vector3d& origin, Item&& item) {
  using step_sums_detail::Moments;
  StepSums out;  // out.plane.residual_moment stays zero
  out.plane.count = n;
  if (n == 0) return out;
  const Moments m = block_sum(n, Moments{}, [&](std::size_t k, Moments& a) {
    Eigen::Vector3d q, normal;
    double r = 0.0, w = 0.0;
    item(k, q, normal, r, w);
    const Eigen::Vector3d d = q - origin;
    a.sum += d;
    a.sq += d.squaredNorm();
    a.r2 += r * r;
    Vector6d K;
    K.head<3>() = d.cross(normal);
    K.tail<3>() = normal;
    const step_sums_detail::Upper KK = step_sums_detail::upper_products(K);
    a.S += KK;
    if (w < 1.0) a.down += (1.0 - std::max(w, 0.0)) * KK;
    if (w > 0.0) a.gw += (w * r) * K;
  });
  const double count = static_cast<double>(n);
  const Eigen::Vector3d offset = m.sum / count;  // c - o
  out.plane.centre = origin + offset;
  out.plane.length_scale_mm = std::sqrt(std::max(0.0, m.sq / count - offset.squaredNorm()));
  out.rms_mm = std::sqrt(m.r2 / count);
  const double L = out.plane.length_scale_mm;
  const double inv_length = L > 0.0 ? 1.0 / L : 0.0;
  Matrix6d A = Matrix6d::Identity();
  A.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() * inv_length;
  A.topRightCorner<3, 3>() = cross_matrix(-offset) * inv_length;
  using step_sums_detail::symmetric;
  out.plane.H = A * symmetric(m.S) * A.transpose() / count;
  out.H = A * symmetric(m.S - m.down) * A.transpose();
  out.g = A * m.gw;
  return out;
}

// The sandwich's middle sum psi(r)^2 J J^T / n (PlaneNormalMatrix::residual_moment) and its bread
// sum psi'(r) J J^T / n (PlaneNormalMatrix::bread) about the centre and length scale of `plane`, psi(r) = w r the
// robust score; item as for step_sums. `saturating`: the kernel's score is flat where its weight is below 1 (Huber:
// psi' = 0 there); otherwise (Tukey) the weight stands in for psi'.
template <typename Item>
void residual_moments_of(std::size_t n, bool saturating, PlaneNormalMatrix& plane, Item&& item) {
  using step_sums_detail::Upper;
  if (n == 0 || !(plane.length_scale_mm > 0.0)) return;
  const double inv_length = 1.0 / plane.length_scale_mm;
  struct Sums {
    Upper middle = Upper::Zero(), bread = Upper::Zero();
    Sums& operator+=(const Sums& o) {
      middle += o.middle;
      bread += o.bread;
      return *this;
    }
  };
  const Sums sums = block_sum(n, Sums{}, [&](std::size_t k, Sums& a) {
    Eigen::Vector3d q, normal;
    double r = 0.0, w = 0.0;
    item(k, q, normal, r, w);
    Vector6d J;
    J.head<3>() = (q - plane.centre).cross(normal) * inv_length;
    J.tail<3>() = normal;
    const Upper JJ = step_sums_detail::upper_products(J);
    const double psi = w * r;
    a.middle += (psi * psi) * JJ;
    const double slope = saturating ? (w >= 1.0 ? 1.0 : 0.0) : std::max(w, 0.0);
    if (slope > 0.0) a.bread += slope * JJ;
  });
  plane.residual_moment = step_sums_detail::symmetric(sums.middle) / static_cast<double>(n);
  plane.bread = step_sums_detail::symmetric(sums.bread) / static_cast<double>(n);
}

}  // namespace conform::detail
