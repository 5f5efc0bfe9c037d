#include "start_scoring.h"

#include <algorithm>
#include <cmath>

namespace conform::detail {

double truncated_rms(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                     const IcpReference& reference, double cap) {
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = T * p;
    const Eigen::Vector3f qf = q.cast<float>();
    double d = cap;
    if (qf.allFinite()) {
      const int j = reference.tree().nearest(qf);
      if (j >= 0) d = std::min(cap, (q - reference.points()[static_cast<std::size_t>(j)]).norm());
    }
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(points.size()));
}

std::vector<char> inliers(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                          const IcpReference& reference, double tolerance, double reach) {
  std::vector<char> inside(points.size(), 0);
  const bool has_normals = reference.normals().size() == reference.points().size();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d q = T * points[i];
    const Eigen::Vector3f qf = q.cast<float>();
    if (!qf.allFinite()) continue;
    const int j = reference.tree().nearest(qf);
    if (j < 0) continue;
    const Eigen::Vector3d d = q - reference.points()[static_cast<std::size_t>(j)];
    const double along = has_normals ? std::abs(d.dot(reference.normals()[static_cast<std::size_t>(j)])) : d.norm();
    inside[i] = along <= tolerance && d.norm() <= reach;
  }
  return inside;
}

double share_of(const std::vector<char>& mask) {
  return static_cast<double>(std::count(mask.begin(), mask.end(), 1)) / static_cast<double>(mask.size());
}

OneSided one_sided(const std::vector<char>& best, const std::vector<char>& other) {
  OneSided c;
  for (std::size_t i = 0; i < best.size(); ++i) {
    c.best_only += best[i] && !other[i];
    c.other_only += other[i] && !best[i];
  }
  return c;
}

bool separated(std::size_t best_only, std::size_t other_only, std::size_t n, const MultiStartOptions& o) {
  if (o.separation_z <= 0.0) return false;
  const double b = static_cast<double>(best_only), a = static_cast<double>(other_only);
  return b >= o.separation_min_share * static_cast<double>(n) && b >= o.separation_ratio * a &&
         b - a > o.separation_z * std::sqrt(a + b);
}

bool better(const StartReport& a, const StartReport& b) {
  if (a.inlier_share != b.inlier_share) return a.inlier_share > b.inlier_share;
  return a.score_mm < b.score_mm;
}


double size_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  return box.diagonal().norm();
}

}  // namespace conform::detail
