#include "conform/pipelines/profile_report.h"

#include <algorithm>

namespace conform {
namespace {

ProfileStraightFrame straight_frame(const ProfileCompensationResult& r) {
  const ProfileEdgeCurve& c = r.edge.curve;
  ProfileStraightFrame f;
  f.origin = c.position(c.t_begin());
  const Eigen::Vector3d chord = c.position(c.t_end()) - f.origin;
  if (chord.norm() > 0.0) f.along = chord.normalized();
  const Eigen::Vector3d z = r.local_web ? Eigen::Vector3d::UnitZ() : r.web_normal;
  const Eigen::Vector3d across = z.cross(f.along);  // Eq. (5), on the straight profile
  if (across.norm() > 0.0) f.across = across.normalized();
  return f;
}

std::vector<Eigen::Vector3d> edge_curve(const ProfileEdgeCurve& c) {
  std::vector<Eigen::Vector3d> out;
  const double length = c.length_mm();
  if (!(length > 0.0)) return out;
  const std::size_t n = kProfileReportCurvePoints;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = length * static_cast<double>(i) / static_cast<double>(n - 1);
    out.push_back(c.position(c.approximate_parameter_at(s)));
  }
  return out;
}

ProfileFeatureFigure feature_figure(const ProfileFeatureResult& r, const ProfileStraightFrame& frame) {
  ProfileFeatureFigure f;
  f.id = r.id;
  f.type = to_string(r.type);
  f.mapped = r.mapped;
  for (std::size_t i = 0; i < r.designed.size() && i < r.mapped.size(); ++i) {
    f.nominal.push_back(frame.at(r.designed[i]));
    f.max_displacement_mm = std::max(f.max_displacement_mm, (r.mapped[i] - f.nominal.back()).norm());
  }
  if (r.has_centre) {
    f.designed = r.designed_centre;
    f.mapped_at = r.centre;
  } else if (!r.designed.empty() && !r.mapped.empty()) {
    f.designed = r.designed.front();
    f.mapped_at = r.mapped.front();
  }
  f.nominal_at = frame.at(f.designed);
  f.displacement_mm = (f.mapped_at - f.nominal_at).norm();
  f.max_displacement_mm = std::max(f.max_displacement_mm, f.displacement_mm);
  return f;
}

}  // namespace

ProfileReportFigures profile_report_figures(const ProfileJobResult& job) {
  const ProfileCompensationResult& r = job.compensation;
  ProfileReportFigures f;
  f.edge = job.edge;
  f.second_edge = job.second_edge;
  f.edge_curve = edge_curve(r.edge.curve);
  f.straight = straight_frame(r);
  for (const ProfileFeatureResult& feature : r.features) f.features.push_back(feature_figure(feature, f.straight));
  return f;
}

}  // namespace conform
