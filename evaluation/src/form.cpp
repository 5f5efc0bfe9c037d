#include "conform/evaluation/form.h"

#include <algorithm>
#include <cmath>

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
