#include "conform/compensation/profile_edge.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "conform/core/error.h"

namespace conform {

const char* to_string(ProfileEdgeModel model) {
  switch (model) {
    case ProfileEdgeModel::kAuto:
      return "auto";
    case ProfileEdgeModel::kCubic:
      return "cubic";
    case ProfileEdgeModel::kSpline:
      return "spline";
  }
  return "unknown";
}

bool parse_profile_edge_model(const std::string& text, ProfileEdgeModel* model) {
  for (ProfileEdgeModel m : {ProfileEdgeModel::kAuto, ProfileEdgeModel::kCubic, ProfileEdgeModel::kSpline}) {
    if (text == to_string(m)) {
      *model = m;
      return true;
    }
  }
  return false;
}

ProfileEdgeCurve ProfileEdgeCurve::cubic(PolynomialCurve curve, int length_segments, const Eigen::Vector3d& origin) {
  if (length_segments < 1) throw Error("profile edge: the cubic's arc-length table needs at least 1 segment");
  ProfileEdgeCurve out;
  out.model_ = ProfileEdgeModel::kCubic;
  out.polynomial_ = std::move(curve);
  out.origin_ = origin;
  std::vector<double> breaks(static_cast<std::size_t>(length_segments) + 1);
  for (std::size_t k = 0; k < breaks.size(); ++k) breaks[k] = static_cast<double>(k) / length_segments;
  out.tabulate(std::move(breaks));
  return out;
}

ProfileEdgeCurve ProfileEdgeCurve::spline(BSplineCurve curve, const Eigen::Vector3d& origin) {
  if (curve.closed()) throw Error("profile edge: the edge spline must be open");
  ProfileEdgeCurve out;
  out.model_ = ProfileEdgeModel::kSpline;
  out.bspline_ = std::move(curve);
  out.origin_ = origin;
  const int spans = out.bspline_.spans();
  std::vector<double> breaks(static_cast<std::size_t>(spans) + 1);
  for (int k = 0; k <= spans; ++k)
    breaks[static_cast<std::size_t>(k)] = out.bspline_.u_begin() + k * out.bspline_.knot_spacing();
  breaks.back() = out.bspline_.u_end();
  out.tabulate(std::move(breaks));
  return out;
}

void ProfileEdgeCurve::tabulate(std::vector<double> breaks) {
  t_ = std::move(breaks);
  s_.assign(t_.size(), 0.0);
  const SpeedFunction speed = [this](double t) { return this->speed(t); };
  for (std::size_t k = 1; k < t_.size(); ++k) s_[k] = s_[k - 1] + arc_length(speed, t_[k - 1], t_[k]);
}

Eigen::Vector3d ProfileEdgeCurve::position(double t) const { return origin_ + local_derivative(t, 0); }

Eigen::Vector3d ProfileEdgeCurve::derivative(double t, int order) const {
  return order == 0 ? position(t) : local_derivative(t, order);
}

Eigen::Vector3d ProfileEdgeCurve::local_derivative(double t, int order) const {
  return model_ == ProfileEdgeModel::kSpline ? bspline_.derivative(t, order) : polynomial_.derivative(t, order);
}

std::size_t ProfileEdgeCurve::segment_of_length(double s_mm) const {
  const auto it = std::upper_bound(s_.begin(), s_.end(), s_mm);
  const std::size_t k = it == s_.begin() ? 0 : static_cast<std::size_t>(it - s_.begin()) - 1;
  return std::min(k, s_.size() - 2);
}

double ProfileEdgeCurve::arc_length_at(double t) const {
  t = std::clamp(t, t_begin(), t_end());
  const auto it = std::upper_bound(t_.begin(), t_.end(), t);
  const std::size_t k = std::min(it == t_.begin() ? 0 : static_cast<std::size_t>(it - t_.begin()) - 1, t_.size() - 2);
  const SpeedFunction speed = [this](double u) { return this->speed(u); };
  return s_[k] + arc_length(speed, t_[k], t);
}

ArcLengthInverse ProfileEdgeCurve::parameter_at(double s_mm, double tolerance_mm) const {
  if (!std::isfinite(s_mm) || s_mm < -tolerance_mm || s_mm > length_mm() + tolerance_mm) {
    char text[200];
    std::snprintf(text, sizeof(text), "Ty = %.3f mm lies beyond the measured edge, which is %.3f mm long", s_mm,
                  length_mm());
    throw Error(text);
  }
  const double s = std::clamp(s_mm, 0.0, length_mm());
  const std::size_t k = segment_of_length(s);
  const SpeedFunction speed = [this](double u) { return this->speed(u); };
  ArcLengthInverse inverse = parameter_at_arc_length(speed, t_[k], t_[k + 1], s - s_[k], tolerance_mm);
  return inverse;
}

double ProfileEdgeCurve::approximate_parameter_at(double s_mm) const {
  const double s = std::clamp(s_mm, 0.0, length_mm());
  const std::size_t k = segment_of_length(s);
  const double span = s_[k + 1] - s_[k];
  const double f = span > 0.0 ? (s - s_[k]) / span : 0.0;
  return t_[k] + f * (t_[k + 1] - t_[k]);
}

}  // namespace conform
