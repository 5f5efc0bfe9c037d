#include "icp_step.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>

#include "block_sum.h"
#include "conform/registration/horn.h"
#include "gicp.h"
#include "step_sums.h"

namespace conform::detail {

namespace {

struct NormalEquations {
  Matrix6d H = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
  NormalEquations& operator+=(const NormalEquations& o) {
    H += o.H;
    g += o.g;
    return *this;
  }
};

// The rigid motion p -> R(w) (p - c) + c + v of the scaled twist x = (w L, v).
Eigen::Isometry3d twist_motion(const Vector6d& x, const Eigen::Vector3d& c, double length_scale_mm) {
  const Eigen::Vector3d w = x.head<3>() / length_scale_mm;
  const double angle = w.norm();
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  if (angle > 0.0) delta.linear() = Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
  delta.translation() = c + x.tail<3>() - delta.linear() * c;
  return delta;
}

}  // namespace

Eigen::MatrixXd allowed_basis(const FreeDof& free_dof, const DegeneracyReport& degeneracy, bool freeze) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(6, free_dof.count());
  for (int i = 0, c = 0; i < 6; ++i) {
    if (free_dof.free(i)) P(i, c++) = 1.0;
  }
  if (!freeze || degeneracy.degenerate_basis.empty()) return P;
  // Project the degenerate directions out of the free subspace, then orthonormalise what is left.
  Eigen::MatrixXd Q = P;
  for (const Vector6d& d : degeneracy.degenerate_basis) Q -= d * (d.transpose() * Q);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Q, Eigen::ComputeThinU);
  const auto keep = static_cast<Eigen::Index>(P.cols()) - static_cast<Eigen::Index>(degeneracy.degenerate_basis.size());
  return svd.matrixU().leftCols(keep < 0 ? 0 : keep);
}

Eigen::Isometry3d horn_step(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers,
                            const std::vector<double>& weights) {
  std::vector<Eigen::Vector3d> from(inliers.size()), to(inliers.size());
  for (std::size_t k = 0; k < inliers.size(); ++k) {
    from[k] = pairs[inliers[k]].q;
    to[k] = pairs[inliers[k]].target;
  }
  return horn_transform(from, to, weights).T_ref_scan;
}

Eigen::Isometry3d gauss_newton_step(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers,
                                    const std::vector<double>& weights, IcpMethod method, const Eigen::Vector3d& centre,
                                    double length_scale_mm, const Eigen::MatrixXd& basis, double gicp_epsilon) {
  if (basis.cols() == 0 || !(length_scale_mm > 0.0)) return Eigen::Isometry3d::Identity();
  const double inv_length = 1.0 / length_scale_mm;
  const NormalEquations sums = block_sum(inliers.size(), NormalEquations{}, [&](std::size_t k, NormalEquations& e) {
    const Pair& p = pairs[inliers[k]];
    const double w = weights[k];
    if (w <= 0.0) return;
    const Eigen::Vector3d a = (p.q - centre) * inv_length;
    if (method == IcpMethod::kPointToPoint || method == IcpMethod::kPlaneToPlane) {
      // r = q - target; dq/d(w L, v) = [-[a]x, I] (Besl & McKay's objective, linearised). Plane-to-plane weights it
      // by the inverse of the summed covariances, Eq. (2) of Segal et al. 2009, held fixed during the step.
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() = -cross_matrix(a);
      J.rightCols<3>() = Eigen::Matrix3d::Identity();
      if (method == IcpMethod::kPlaneToPlane) {
        const Eigen::Matrix3d omega = plane_to_plane_information(p.normal, p.scan_normal, gicp_epsilon);
        const Eigen::Matrix<double, 3, 6> OJ = omega * J;
        e.H.noalias() += w * J.transpose() * OJ;
        e.g.noalias() += w * OJ.transpose() * (p.q - p.target);
      } else {
        e.H.noalias() += w * J.transpose() * J;
        e.g.noalias() += w * J.transpose() * (p.q - p.target);
      }
    } else {
      // r = n . (q - target); dr/d(w L, v) = [a x n, n] (Chen & Medioni 1992, small-angle linearisation).
      Vector6d J;
      J.head<3>() = a.cross(p.normal);
      J.tail<3>() = p.normal;
      e.H.noalias() += w * J * J.transpose();
      e.g.noalias() += w * p.residual * J;
    }
  });
  return solve_step(sums.H, sums.g, centre, length_scale_mm, basis);
}

Eigen::Isometry3d solve_step(const Matrix6d& H, const Vector6d& g, const Eigen::Vector3d& centre,
                             double length_scale_mm, const Eigen::MatrixXd& basis) {
  if (basis.cols() == 0 || !(length_scale_mm > 0.0)) return Eigen::Isometry3d::Identity();
  const Eigen::MatrixXd Hb = basis.transpose() * H * basis;
  const Eigen::VectorXd gb = basis.transpose() * g;
  const Eigen::VectorXd y = Hb.ldlt().solve(-gb);
  if (!y.allFinite()) return Eigen::Isometry3d::Identity();
  return twist_motion(basis * y, centre, length_scale_mm);
}

}  // namespace conform::detail
