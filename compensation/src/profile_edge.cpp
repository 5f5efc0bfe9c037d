#include "conform/compensation/profile_edge.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "conform/core/error.h"
#include "conform/fitting/bspline_fit.h"

namespace conform {
namespace {

ProfileEdgeResidual residual_of(const std::vector<double>& residual_mm) {
  ProfileEdgeResidual out;
  out.fitted = true;
  double sum = 0.0;
  for (std::size_t i = 0; i < residual_mm.size(); ++i) {
    sum += residual_mm[i] * residual_mm[i];
    if (residual_mm[i] > out.max_mm) {
      out.max_mm = residual_mm[i];
      out.max_index = static_cast<int>(i);
    }
  }
  out.rms_mm = residual_mm.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(residual_mm.size()));
  return out;
}

std::string format_selection(const char* format, double a, double ratio, double b) {
  char text[200];
  std::snprintf(text, sizeof(text), format, a, ratio, b);
  return text;
}

}  // namespace

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

ProfileEdgeCurve ProfileEdgeCurve::cubic(PolynomialCurve curve, int length_segments) {
  if (length_segments < 1) throw Error("profile edge: the cubic's arc-length table needs at least 1 segment");
  ProfileEdgeCurve out;
  out.model_ = ProfileEdgeModel::kCubic;
  out.polynomial_ = std::move(curve);
  std::vector<double> breaks(static_cast<std::size_t>(length_segments) + 1);
  for (std::size_t k = 0; k < breaks.size(); ++k) breaks[k] = static_cast<double>(k) / length_segments;
  out.tabulate(std::move(breaks));
  return out;
}

ProfileEdgeCurve ProfileEdgeCurve::spline(BSplineCurve curve) {
  if (curve.closed()) throw Error("profile edge: the edge spline must be open");
  ProfileEdgeCurve out;
  out.model_ = ProfileEdgeModel::kSpline;
  out.bspline_ = std::move(curve);
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

Eigen::Vector3d ProfileEdgeCurve::position(double t) const { return derivative(t, 0); }

Eigen::Vector3d ProfileEdgeCurve::derivative(double t, int order) const {
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

bool ProfileEdgeFitOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!points.IsValid(&problem)) {
  } else if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) {
    problem = "noise_mm must be >= 0 (0: estimate it)";
  } else if (spline_control_points != 0 && spline_control_points < 4) {
    problem = "spline_control_points must be 0 (automatic) or at least 4";
  } else if (!(auto_ratio > 1.0) || !std::isfinite(auto_ratio)) {
    problem = "auto_ratio must be > 1";
  } else if (cubic_length_segments < 1) {
    problem = "cubic_length_segments must be at least 1";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

ProfileEdgeFit fit_profile_edge(const std::vector<Eigen::Vector3d>& points, const ProfileEdgeFitOptions& options,
                                const std::string& source) {
  std::string problem;
  if (!options.IsValid(&problem)) throw Error(source + ": invalid edge-fit options: " + problem);
  ProfileEdgeFit fit;
  fit.points = check_profile_edge_points(points, options.points, source);
  fit.noise_mm = options.noise_mm > 0.0 ? options.noise_mm : fit.points.noise_mm;

  const PolynomialCurveFit cubic = fit_polynomial_curve(points, PolynomialCurveOptions{});  // Eq. (1)-(2)
  if (!cubic.ok) throw Error(source + ": the cubic edge fit failed: " + cubic.termination);
  fit.cubic = ProfileEdgeCurve::cubic(cubic.curve, options.cubic_length_segments);
  fit.cubic_fit = residual_of(cubic.residual_mm);

  ProfileEdgeCurve spline;
  if (options.model != ProfileEdgeModel::kCubic) {
    BSplineFitOptions spline_options;
    spline_options.control_points = options.spline_control_points;
    // splprep's s for noise sigma per coordinate is 3 n sigma^2 (bspline_fit.h); over chord-length parameters the
    // noise along the edge goes into the parameters, so only the two components across it remain: 2 n sigma^2.
    spline_options.smoothing_mm2 = 2.0 * static_cast<double>(points.size()) * fit.noise_mm * fit.noise_mm;
    const BSplineFit bspline = fit_bspline_curve(points, spline_options);
    if (!bspline.ok) throw Error(source + ": the spline edge fit failed: " + bspline.termination);
    spline = ProfileEdgeCurve::spline(bspline.curve);
    fit.spline_fit = residual_of(bspline.residual_mm);
  }

  fit.model = options.model;
  if (options.model == ProfileEdgeModel::kAuto) {
    const bool cubic_enough = fit.cubic_fit.rms_mm <= options.auto_ratio * fit.spline_fit.rms_mm;
    fit.model = cubic_enough ? ProfileEdgeModel::kCubic : ProfileEdgeModel::kSpline;
    fit.selection = format_selection(cubic_enough ? "auto: cubic RMS %.4f mm <= %.2f x spline RMS %.4f mm"
                                                  : "auto: cubic RMS %.4f mm > %.2f x spline RMS %.4f mm",
                                     fit.cubic_fit.rms_mm, options.auto_ratio, fit.spline_fit.rms_mm);
  } else {
    fit.selection = std::string("asked for: ") + to_string(options.model);
  }
  const bool use_spline = fit.model == ProfileEdgeModel::kSpline;
  fit.curve = use_spline ? spline : fit.cubic;
  fit.rms_mm = use_spline ? fit.spline_fit.rms_mm : fit.cubic_fit.rms_mm;
  fit.max_mm = use_spline ? fit.spline_fit.max_mm : fit.cubic_fit.max_mm;
  return fit;
}

}  // namespace conform
