#include "conform/toolpath/intersection/local_quadric.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "conform/core/error.h"

namespace conform {

double LocalQuadric::height(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = (p - origin) / scale;
  const double x = d.dot(u);
  const double y = d.dot(v);
  const double f = c[0] * x * x + c[1] * x * y + c[2] * y * y + c[3] * x + c[4] * y + c[5];
  return scale * (d.dot(n) - f);
}

Eigen::Vector3d LocalQuadric::gradient(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d d = (p - origin) / scale;
  const double x = d.dot(u);
  const double y = d.dot(v);
  const double fx = 2.0 * c[0] * x + c[1] * y + c[3];
  const double fy = c[1] * x + 2.0 * c[2] * y + c[4];
  return n - fx * u - fy * v;
}

LocalQuadric fit_local_quadric(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                               bool quadric) {
  if (points.size() < 3) throw Error("local surface fit: fewer than 3 neighbouring vertices");
  LocalQuadric patch;
  patch.origin = origin;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : points) centroid += q;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double scale = 0.0;
  for (const Eigen::Vector3d& q : points) {
    covariance += (q - centroid) * (q - centroid).transpose();
    scale = std::max(scale, (q - origin).norm());
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  patch.n = solver.eigenvectors().col(0).normalized();
  patch.v = solver.eigenvectors().col(1).normalized();
  patch.u = patch.n.cross(patch.v);
  patch.scale = scale > 0.0 ? scale : 1.0;
  // The plane through the centroid, in case the quadric cannot be fitted.
  patch.c[5] = (centroid - origin).dot(patch.n) / patch.scale;
  if (!quadric || points.size() < 6) return patch;
  Eigen::MatrixXd A(static_cast<Eigen::Index>(points.size()), 6);
  Eigen::VectorXd h(static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d d = (points[i] - origin) / patch.scale;
    const double x = d.dot(patch.u);
    const double y = d.dot(patch.v);
    const auto r = static_cast<Eigen::Index>(i);
    A.row(r) << x * x, x * y, y * y, x, y, 1.0;
    h(r) = d.dot(patch.n);
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 6) return patch;
  const Eigen::VectorXd coefficients = qr.solve(h);
  for (int i = 0; i < 6; ++i) patch.c[i] = coefficients(i);
  patch.quadric = true;
  if (points.size() > 6) {
    // sigma^2 (A^T A)^-1 for the slopes: how far the noise can tilt the normal at the origin.
    const double variance = (A * coefficients - h).squaredNorm() / static_cast<double>(points.size() - 6);
    const Eigen::Matrix<double, 6, 6> inverse = (A.transpose() * A).inverse();
    const double slopes = variance * (inverse(3, 3) + inverse(4, 4));
    if (std::isfinite(slopes) && slopes >= 0.0) patch.normal_sigma_rad = std::sqrt(slopes);
  }
  return patch;
}

}  // namespace conform
