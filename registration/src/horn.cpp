#include "conform/registration/horn.h"

#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"

namespace conform {

namespace {

// Points count as collinear when their spread across the main direction is below this fraction of the spread along
// it (variances, so 1e-12 is a width of 1e-6 of the length): the rotation about that line is then undetermined.
constexpr double kCollinear = 1e-12;

// Horn 1987, Eq. (36)-(39): the symmetric 4x4 matrix whose largest eigenvector is the rotation quaternion, built
// from the cross-covariance S = sum w (scan - scan_mean)(ref - ref_mean)^T.
Eigen::Matrix4d horn_matrix(const Eigen::Matrix3d& S) {
  const double xx = S(0, 0), xy = S(0, 1), xz = S(0, 2);
  const double yx = S(1, 0), yy = S(1, 1), yz = S(1, 2);
  const double zx = S(2, 0), zy = S(2, 1), zz = S(2, 2);
  Eigen::Matrix4d N;
  N << xx + yy + zz, yz - zy, zx - xz, xy - yx,  //
      yz - zy, xx - yy - zz, xy + yx, zx + xz,   //
      zx - xz, xy + yx, -xx + yy - zz, yz + zy,  //
      xy - yx, zx + xz, yz + zy, -xx - yy + zz;
  return N;
}

}  // namespace

HornResult horn_transform(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& ref,
                          const std::vector<double>& weights) {
  if (scan.size() != ref.size()) {
    throw Error("horn_transform: " + std::to_string(scan.size()) + " scan points but " + std::to_string(ref.size()) +
                " reference points; they must pair up");
  }
  if (!weights.empty() && weights.size() != scan.size()) {
    throw Error("horn_transform: " + std::to_string(weights.size()) + " weights for " + std::to_string(scan.size()) +
                " point pairs");
  }
  const auto weight = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };
  double total = 0.0;
  std::size_t count = 0;
  Eigen::Vector3d scan_mean = Eigen::Vector3d::Zero(), ref_mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const double w = weight(i);
    if (!std::isfinite(w) || w < 0.0) throw Error("horn_transform: weight " + std::to_string(i) + " is not >= 0");
    total += w;
    count += w > 0.0 ? 1 : 0;
    scan_mean += w * scan[i];
    ref_mean += w * ref[i];
  }
  HornResult result;
  if (count == 0 || !(total > 0.0)) return result;
  scan_mean /= total;
  ref_mean /= total;

  Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d scan_cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < scan.size(); ++i) {
    const Eigen::Vector3d a = scan[i] - scan_mean;
    S.noalias() += weight(i) * a * (ref[i] - ref_mean).transpose();
    scan_cov.noalias() += weight(i) * a * a.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(horn_matrix(S));
  const Eigen::Vector4d q = solver.eigenvectors().col(3);  // eigenvalues ascend: the largest is last
  const Eigen::Quaterniond rotation(q(0), q(1), q(2), q(3));
  result.T_ref_scan.linear() = rotation.normalized().toRotationMatrix();
  result.T_ref_scan.translation() = ref_mean - result.T_ref_scan.linear() * scan_mean;

  const Eigen::Vector3d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scan_cov).eigenvalues();
  result.well_posed = count >= 3 && spread(1) > kCollinear * spread(2);
  return result;
}

}  // namespace conform
