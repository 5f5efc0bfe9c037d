#include "conform/pipelines/saddle_report.h"

#include <algorithm>
#include <cmath>

#include "conform/toolpath/saddle_curve.h"

namespace conform {
namespace {

constexpr double kDegPerRad = 57.29577951308232;

}  // namespace

Eigen::Vector3d saddle_torch_direction(double theta_rad, double pose_rad) {
  const Eigen::Vector3d n_p(std::sin(theta_rad), std::cos(theta_rad), 0.0);
  return std::cos(pose_rad) * Eigen::Vector3d::UnitZ() + std::sin(pose_rad) * n_p;
}

SaddleReportFigures saddle_report_figures(const SaddleJobOptions& options, const SaddleJobResult& job) {
  SaddleReportFigures f;
  const std::vector<SaddlePoint>& points = job.saddle.points;
  if (points.empty()) return f;
  const SaddleCurve curve(options.saddle.geometry);
  for (const SaddlePoint& p : points) {
    f.max_position_error_mm = std::max(f.max_position_error_mm, (p.position - curve.point(p.theta_rad)).norm());
    const double pose = curve.pose(p.theta_rad, options.saddle.start_pose_rad);
    f.max_pose_error_deg = std::max(f.max_pose_error_deg, std::abs(p.pose_rad - pose) * kDegPerRad);
  }
  for (const std::size_t i : spread_indices(points.size(), kSaddleReportPoints)) {
    const SaddlePoint& p = points[i];
    f.path.push_back(p.position);
    f.theta_deg.push_back(p.theta_rad * kDegPerRad);
    f.z_mm.push_back(p.position.z());
    f.closed_z_mm.push_back(curve.point(p.theta_rad).z());
    f.pose_deg.push_back(p.pose_rad * kDegPerRad);
    f.closed_pose_deg.push_back(curve.pose(p.theta_rad, options.saddle.start_pose_rad) * kDegPerRad);
    f.step_mm.push_back(p.step_mm);
  }
  // The last point is the first again (theta 2 pi): one glyph there is enough.
  for (const std::size_t i : spread_indices(points.size() - 1, kSaddleReportGlyphs)) {
    f.torch.origins.push_back(points[i].position);
    f.torch.directions.push_back(saddle_torch_direction(points[i].theta_rad, points[i].pose_rad));
  }
  return f;
}

}  // namespace conform
