#pragma once
// The normalised point-to-plane normal matrix (degeneracy.h) over any sequence of (point, normal) pairs.

#include <cmath>
#include <cstddef>
#include <type_traits>

#include "block_sum.h"
#include "conform/registration/degeneracy.h"

namespace conform::detail {

struct MomentSums {
  Matrix6d H = Matrix6d::Zero();
  Matrix6d M = Matrix6d::Zero();
  MomentSums& operator+=(const MomentSums& o) {
    H += o.H;
    M += o.M;
    return *this;
  }
};

struct PointSums {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double sq = 0.0;
  PointSums& operator+=(const PointSums& o) {
    sum += o.sum;
    sq += o.sq;
    return *this;
  }
};

// point(i), normal(i) for i in [0, n): references to Eigen::Vector3d; residual(i): its residual, mm (a null pointer:
// no residual moment).
template <typename PointAt, typename NormalAt, typename ResidualAt>
PlaneNormalMatrix plane_normal_matrix_of(std::size_t n, PointAt&& point, NormalAt&& normal, ResidualAt&& residual) {
  PlaneNormalMatrix m;
  m.count = n;
  if (n == 0) return m;
  const double count = static_cast<double>(n);
  m.centre = block_sum(n, PointSums{}, [&](std::size_t i, PointSums& a) { a.sum += point(i); }).sum / count;
  const double sq =
      block_sum(n, PointSums{}, [&](std::size_t i, PointSums& a) { a.sq += (point(i) - m.centre).squaredNorm(); }).sq;
  m.length_scale_mm = std::sqrt(sq / count);
  const double inv_length = m.length_scale_mm > 0.0 ? 1.0 / m.length_scale_mm : 0.0;
  constexpr bool kWithResiduals = !std::is_same_v<std::decay_t<ResidualAt>, std::nullptr_t>;
  const MomentSums sums = block_sum(n, MomentSums{}, [&](std::size_t i, MomentSums& a) {
    Vector6d J;
    J.head<3>() = (point(i) - m.centre).cross(normal(i)) * inv_length;
    J.tail<3>() = normal(i);
    a.H.noalias() += J * J.transpose();
    if constexpr (kWithResiduals) {
      const double r = residual(i);
      a.M.noalias() += (r * r) * J * J.transpose();
    }
  });
  m.H = sums.H / count;
  m.residual_moment = sums.M / count;
  return m;
}

// The cluster-robust middle of the sandwich (degeneracy.h, PlaneNormalMatrix::cluster_moment) over `clusters`
// contiguous runs of [0, n) (Liang & Zeger 1986, Eq. (2.5)'s middle term, with its small-sample factor K/(K-1)):
// in a spatially ordered scan (z_order.h) a run is a compact patch. psi(i): the pair's robust score, the weighted
// residual w_i r_i (mm). Sets matrix.cluster_moment and matrix.clusters; fewer than 2 runs: leaves them zero.
template <typename PointAt, typename NormalAt, typename ScoreAt>
void add_cluster_moment(std::size_t n, PointAt&& point, NormalAt&& normal, ScoreAt&& psi, std::size_t clusters,
                        PlaneNormalMatrix& matrix) {
  clusters = clusters < n ? clusters : n;
  if (clusters < 2 || !(matrix.length_scale_mm > 0.0)) return;
  const double inv_length = 1.0 / matrix.length_scale_mm;
  Matrix6d B = Matrix6d::Zero();
  for (std::size_t b = 0; b < clusters; ++b) {
    Vector6d g = Vector6d::Zero();
    for (std::size_t i = b * n / clusters, end = (b + 1) * n / clusters; i < end; ++i) {
      const double r = psi(i);
      g.head<3>() += r * (point(i) - matrix.centre).cross(normal(i)) * inv_length;
      g.tail<3>() += r * normal(i);
    }
    B.noalias() += g * g.transpose();
  }
  const double K = static_cast<double>(clusters);
  matrix.cluster_moment = B * (K / (K - 1.0)) / static_cast<double>(n);
  matrix.clusters = clusters;
}

// Without residuals: no residual moment.
template <typename PointAt, typename NormalAt>
PlaneNormalMatrix plane_normal_matrix_of(std::size_t n, PointAt&& point, NormalAt&& normal) {
  return plane_normal_matrix_of(n, point, normal, nullptr);
}

}  // namespace conform::detail
