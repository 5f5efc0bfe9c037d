#include "conform/evaluation/form.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/evaluation/statistics.h"

namespace conform {

PlaneFit fit_plane(const std::vector<Eigen::Vector3d>& points) {
  PlaneFit fit;
  if (points.size() < 3) return fit;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - centroid;
    covariance += d * d.transpose();
  }
  covariance /= static_cast<double>(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
  fit.point = centroid;
  fit.normal = eigen.eigenvectors().col(0).normalized();
  fit.rms_mm = std::sqrt(std::max(values(0), 0.0));
  fit.ok = values(2) > 0.0 && values(1) > 1e-12 * values(2);
  return fit;
}

SphereFit fit_sphere(const std::vector<Eigen::Vector3d>& points) {
  SphereFit fit;
  if (points.size() < 4) return fit;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  // Algebraic start: |q|^2 = 2 c.q + k with q = p - centroid, k = r^2 - |c|^2.
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = p - centroid;
    const Eigen::Vector4d row(2.0 * q.x(), 2.0 * q.y(), 2.0 * q.z(), 1.0);
    normal += row * row.transpose();
    rhs += row * q.squaredNorm();
  }
  const Eigen::LDLT<Eigen::Matrix4d> solver(normal);
  if (solver.info() != Eigen::Success || !(std::abs(solver.vectorD().minCoeff()) > 1e-12 * normal.norm())) return fit;
  const Eigen::Vector4d a = solver.solve(rhs);
  Eigen::Vector3d c = a.head<3>();
  double r2 = a(3) + c.squaredNorm();
  if (!(r2 > 0.0)) return fit;
  double r = std::sqrt(r2);
  // Gauss-Newton on e_i = |q_i - c| - r; d e / d c = -(q_i - c) / |q_i - c|, d e / d r = -1.
  bool converged = false;
  for (int step = 0; step < 50 && !converged; ++step) {
    Eigen::Matrix4d jtj = Eigen::Matrix4d::Zero();
    Eigen::Vector4d jte = Eigen::Vector4d::Zero();
    for (const Eigen::Vector3d& p : points) {
      const Eigen::Vector3d d = p - centroid - c;
      const double n = d.norm();
      if (n == 0.0) continue;
      const Eigen::Vector4d j(-d.x() / n, -d.y() / n, -d.z() / n, -1.0);
      jtj += j * j.transpose();
      jte += j * (n - r);
    }
    const Eigen::Vector4d delta = jtj.ldlt().solve(-jte);
    if (!delta.allFinite()) return fit;
    c += delta.head<3>();
    r += delta(3);
    converged = delta.norm() < 1e-12 * std::max(r, 1.0);
  }
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) sum += std::pow((p - centroid - c).norm() - r, 2);
  fit.centre = centroid + c;
  fit.radius_mm = r;
  fit.rms_mm = std::sqrt(sum / static_cast<double>(points.size()));
  fit.ok = converged && r > 0.0;
  return fit;
}

FormZone form_zone(const std::vector<double>& residuals_mm, double trim_share) {
  if (!(trim_share >= 0.0 && trim_share < 0.5)) throw Error("form_zone: the trim share must be in [0, 0.5)");
  FormZone zone;
  zone.trim_share = trim_share;
  std::vector<double> sorted;
  sorted.reserve(residuals_mm.size());
  for (const double r : residuals_mm) {
    if (std::isfinite(r)) sorted.push_back(r);
  }
  zone.count = sorted.size();
  if (sorted.empty()) return zone;
  std::sort(sorted.begin(), sorted.end());
  zone.lower_mm = percentile_of_sorted(sorted, 50.0 * trim_share);
  zone.upper_mm = percentile_of_sorted(sorted, 100.0 - 50.0 * trim_share);
  zone.width_mm = zone.upper_mm - zone.lower_mm;
  zone.full_width_mm = sorted.back() - sorted.front();
  return zone;
}

}  // namespace conform
