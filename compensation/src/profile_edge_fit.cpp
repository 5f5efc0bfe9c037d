// fit_profile_edge: the robust edge fit of profile_edge.h (centring, projection parameters, reweighting, BIC).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "conform/compensation/profile_edge.h"
#include "conform/core/error.h"
#include "conform/fitting/bspline_fit.h"

namespace conform {
namespace {

constexpr double kOutlierWeight = 1e-6;     // w of a rejected point: w^2 = 1e-12, no pull on the spline
constexpr double kRayleighMedian = 1.1774;  // median of |r| for r gaussian in 2 components of sigma 1
constexpr std::size_t kListedOutliers = 20;

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto middle = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

// The points kept by the check, centred on their centroid, with their parameters u (mm along the main axis from the
// first one: projection-based, so noise along the edge does not add up as it does in chord length).
struct Prepared {
  std::vector<Eigen::Vector3d> local;
  std::vector<int> index;  // input index of each
  std::vector<double> u;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  double u_end = 0.0;
};

Prepared prepare(const std::vector<Eigen::Vector3d>& points, const ProfileEdgePointsCheck& check) {
  Prepared p;
  p.index = check.order;
  const Eigen::Vector3d first = points[static_cast<std::size_t>(check.order.front())];
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i : check.order) mean += points[static_cast<std::size_t>(i)] - first;
  p.origin = first + mean / static_cast<double>(check.order.size());
  for (std::size_t k = 0; k < check.order.size(); ++k) {
    p.local.push_back(points[static_cast<std::size_t>(check.order[k])] - p.origin);
    p.u.push_back(check.along_mm[k] - check.along_mm.front());
  }
  p.u_end = p.u.back();
  p.axis = check.axis;
  return p;
}

struct ModelFit {
  ProfileEdgeCurve curve;
  std::vector<double> residual_mm;  // every prepared point, inlier or not
  bool smoothing_met = true;
  double dof = 4.0;  // per coordinate
};

ModelFit fit_cubic(const Prepared& p, const std::vector<char>& inlier, int segments) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> t;
  for (std::size_t k = 0; k < p.local.size(); ++k) {
    if (!inlier[k]) continue;
    points.push_back(p.local[k]);
    t.push_back(p.u[k] / p.u_end);
  }
  const PolynomialCurveFit fit = fit_polynomial_curve(points, t, PolynomialCurveOptions{});  // Eq. (1)-(2)
  if (!fit.ok) throw Error("the cubic edge fit failed: " + fit.termination);
  ModelFit out;
  out.curve = ProfileEdgeCurve::cubic(fit.curve, segments, p.origin);
  for (std::size_t k = 0; k < p.local.size(); ++k) {
    out.residual_mm.push_back((p.local[k] - fit.curve.position(p.u[k] / p.u_end)).norm());
  }
  return out;
}

ModelFit fit_spline(const Prepared& p, const std::vector<char>& inlier, double sigma, int control_points,
                    bool want_dof) {
  BSplineFitOptions o;
  o.control_points = control_points;
  o.parameters = p.u;
  o.weights.assign(p.local.size(), 1.0);
  std::size_t inliers = 0;
  for (std::size_t k = 0; k < p.local.size(); ++k) {
    if (inlier[k]) ++inliers;
    if (!inlier[k]) o.weights[k] = kOutlierWeight;
  }
  // splprep's s for noise sigma per coordinate is 3 n sigma^2 (bspline_fit.h); with parameters from the projection on
  // the axis the noise along the edge goes into the parameters, so only the two components across it remain.
  o.smoothing_mm2 = 2.0 * static_cast<double>(inliers) * sigma * sigma;
  o.effective_dof = want_dof;
  o.smoothing_tolerance = 1e-3;  // the target itself is an estimate (sigma from second differences, +-3 %)
  const BSplineFit fit = fit_bspline_curve(p.local, o);
  if (!fit.ok) throw Error("the spline edge fit failed: " + fit.termination);
  ModelFit out;
  out.curve = ProfileEdgeCurve::spline(fit.curve, p.origin);
  out.residual_mm = fit.residual_mm;
  // Not met only when the closest fit stays above the target (detail finer than the knots); a curve that is smoother
  // than the noise allows everywhere (a straight edge) is fine.
  out.smoothing_met = fit.converged || fit.weighted_ss_mm2 <= o.smoothing_mm2;
  out.dof = fit.effective_dof;
  return out;
}


ProfileEdgeResidual residual_of(const ModelFit& m, const Prepared& p, const std::vector<char>& inlier) {
  ProfileEdgeResidual out;
  out.fitted = true;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < m.residual_mm.size(); ++k) {
    if (!inlier[k]) continue;
    const double r = m.residual_mm[k];
    sum += r * r;
    ++n;
    if (r > out.max_mm) out.max_mm = r, out.max_index = p.index[k];
  }
  out.rms_mm = n > 0 ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  // BIC over the 3 n coordinates (Schwarz 1978); the floor keeps an exact fit finite.
  const double big_n = 3.0 * static_cast<double>(n);
  out.dof = m.dof;
  out.bic = big_n * std::log(std::max(sum, 1e-300) / big_n) + 3.0 * m.dof * std::log(big_n);
  return out;
}

// A start that no least-squares fit gives: each point against the line through two robust local points, the
// componentwise medians (u included) of kScreenGroup neighbours before it and of as many after it (both after or both
// before it at the ends), across the axis only. A burst of bad readings, or a third of them, pulls a least-squares
// curve towards itself so much that its residuals no longer tell them apart; medians of neighbours do not move, and
// the line through two of them follows the edge's slope (a plain median of neighbours would not, with uneven gaps).
constexpr std::size_t kScreenGroup = 5;

struct Robust {
  double u = 0.0;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
};

Robust group_median(const Prepared& p, std::size_t lo, std::size_t hi, std::vector<double>* scratch) {
  Robust out;
  const auto median_in_place = [scratch]() {
    const auto middle = scratch->begin() + static_cast<std::ptrdiff_t>(scratch->size() / 2);
    std::nth_element(scratch->begin(), middle, scratch->end());
    return *middle;
  };
  scratch->clear();
  for (std::size_t j = lo; j < hi; ++j) scratch->push_back(p.u[j]);
  out.u = median_in_place();
  for (int d = 0; d < 3; ++d) {
    scratch->clear();
    for (std::size_t j = lo; j < hi; ++j) scratch->push_back(p.local[j][d]);
    out.p[d] = median_in_place();
  }
  return out;
}

// Zero for every point of a scan too short for two groups on one side.
std::vector<double> median_screen_residuals(const Prepared& p) {
  const std::size_t n = p.local.size(), g = kScreenGroup;
  std::vector<double> out(n, 0.0), scratch;
  if (n < 2 * g + 1) return out;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t a_lo = i >= g ? i - g : 0, a_hi = i, b_lo = i + 1, b_hi = std::min(n, i + 1 + g);
    if (i < 2) a_lo = i + 1, a_hi = i + 1 + g, b_lo = a_hi, b_hi = a_hi + g;             // the start: both after
    if (i + 2 >= n) b_lo = i - g, b_hi = i, a_lo = i - 2 * g, a_hi = i - g;                // the end: both before
    const Robust a = group_median(p, a_lo, a_hi, &scratch), b = group_median(p, b_lo, b_hi, &scratch);
    const double span = b.u - a.u;
    const Eigen::Vector3d m = std::abs(span) > 0.0 ? Eigen::Vector3d(a.p + (b.p - a.p) * ((p.u[i] - a.u) / span))
                                                   : Eigen::Vector3d(0.5 * (a.p + b.p));
    Eigen::Vector3d r = p.local[i] - m;
    r -= r.dot(p.axis) * p.axis;
    out[i] = r.norm();
  }
  return out;
}

struct Reweighted {
  ModelFit fit;
  std::vector<char> inlier;
  int passes = 0;
  bool converged = false;
};

// Iterative reweighting with weights 0 or 1: every pass fits the model to the current inliers and re-decides every
// point from that curve (a point wrongly dropped next to a spike comes back once the spike no longer pulls).
template <typename FitFunction>
Reweighted reweight(const Prepared& p, const std::vector<double>& screen, double sigma, const ProfileEdgeFitOptions& o,
                   FitFunction fit_model) {
  Reweighted r;
  r.inlier.assign(p.local.size(), 1);
  const double screen_threshold = std::max(1.08 * o.outlier_threshold_sigma * sigma, o.min_outlier_mm);
  for (std::size_t k = 0; k < screen.size(); ++k) r.inlier[k] = screen[k] <= screen_threshold ? 1 : 0;
  for (r.passes = 1; r.passes <= o.max_reweighting_passes; ++r.passes) {
    r.fit = fit_model(r.inlier);
    const double scale = std::max(sigma, median_of(r.fit.residual_mm) / kRayleighMedian);
    const double threshold = std::max(o.outlier_threshold_sigma * scale, o.min_outlier_mm);
    std::vector<char> next(p.local.size());
    for (std::size_t k = 0; k < next.size(); ++k) next[k] = r.fit.residual_mm[k] <= threshold ? 1 : 0;
    if (next == r.inlier) {
      r.converged = true;
      break;
    }
    r.inlier = std::move(next);
  }
  r.passes = std::min(r.passes, o.max_reweighting_passes);
  return r;
}

double automatic_knot_spacing(const ProfileEdgePointsCheck& check, double sigma) {
  // Enough points per span to average the noise (10 steps), and a span long against the noise: its tangent is
  // then good to ~sigma / (250 sigma) = 0.004 rad before smoothing; 20 mm at least.
  return std::max({10.0 * check.median_spacing_mm, 250.0 * sigma, 20.0});
}

int control_points_for(double length_mm, double spacing_mm, std::size_t n) {
  const double spans = std::ceil(length_mm / spacing_mm);
  const double most = std::max(4.0, static_cast<double>(n));
  return static_cast<int>(std::clamp(spans + 3.0, 4.0, std::min(most, 20000.0)));
}

std::string format(const char* f, double a, double b) {
  char text[240];
  std::snprintf(text, sizeof(text), f, a, b);
  return text;
}

void record_outliers(const Prepared& p, const Reweighted& r, const std::string& source,
                     const ProfileEdgeFitOptions& o, ProfileEdgeFit* fit) {
  fit->reweighting_passes = r.passes;
  fit->reweighting_converged = r.converged;
  for (std::size_t k = 0; k < r.inlier.size(); ++k) {
    if (r.inlier[k]) continue;
    ++fit->outliers;
    if (fit->outlier_indices.size() < kListedOutliers) fit->outlier_indices.push_back(p.index[k]);
  }
  std::sort(fit->outlier_indices.begin(), fit->outlier_indices.end());
  const double fraction = static_cast<double>(fit->outliers) / static_cast<double>(p.local.size());
  if (fraction > o.max_outlier_fraction) {
    char text[300];
    std::snprintf(text, sizeof(text),
                  ": %zu of %zu edge points (%.1f %%) lie off the fitted edge by more than %.1f robust sigmas; more "
                  "than %.0f %% outliers: is this one edge of one profile, measured in one pass?",
                  fit->outliers, p.local.size(), 100.0 * fraction, o.outlier_threshold_sigma,
                  100.0 * o.max_outlier_fraction);
    throw Error(source + text);
  }
  if (!r.converged) {
    fit->warnings.push_back(source + ": the outlier rejection still changed after " + std::to_string(r.passes) +
                            " passes");
  }
}

// The spline, reweighted. Knots tied to the step and the noise; where the spline cannot reach the noise level (detail
// finer than the knots), they are halved, at most twice and never below two steps.
Reweighted robust_spline(const Prepared& p, const std::vector<double>& screen, double sigma,
                         const ProfileEdgeFitOptions& options, ProfileEdgeFit* fit) {
  fit->knot_spacing_mm =
      options.knot_spacing_mm > 0.0 ? options.knot_spacing_mm : automatic_knot_spacing(fit->points, sigma);
  const auto control_points = [&]() {
    return options.spline_control_points > 0 ? options.spline_control_points
                                             : control_points_for(p.u_end, fit->knot_spacing_mm, p.local.size());
  };
  Reweighted robust;
  for (int attempt = 0;; ++attempt) {
    const int m = control_points();
    robust = reweight(p, screen, sigma, options,
                      [&](const std::vector<char>& inlier) { return fit_spline(p, inlier, sigma, m, false); });
    const bool finer = !robust.fit.smoothing_met && options.spline_control_points == 0 &&
                       residual_of(robust.fit, p, robust.inlier).rms_mm > 1.25 * std::sqrt(2.0) * sigma &&
                       options.knot_spacing_mm == 0.0 && attempt < 2 &&
                       fit->knot_spacing_mm >= 4.0 * fit->points.median_spacing_mm;
    if (!finer) break;
    fit->knot_spacing_mm *= 0.5;
  }
  // The effective degrees of freedom for the BIC, once, on the final inliers.
  if (options.model == ProfileEdgeModel::kAuto) robust.fit = fit_spline(p, robust.inlier, sigma, control_points(), true);
  fit->smoothing_converged = robust.fit.smoothing_met;
  fit->spline_fit = residual_of(robust.fit, p, robust.inlier);
  return robust;
}

// The model used (auto: the lower BIC) and a warning when the spline stays above the noise.
void choose_model(const ProfileEdgeFitOptions& options, const ModelFit& spline, double sigma,
                  const std::string& source, ProfileEdgeFit* fit) {
  fit->model = options.model;
  if (options.model == ProfileEdgeModel::kAuto) {
    const bool cubic_wins = fit->cubic_fit.bic <= fit->spline_fit.bic;
    fit->model = cubic_wins ? ProfileEdgeModel::kCubic : ProfileEdgeModel::kSpline;
    fit->selection =
        format(cubic_wins ? "auto: BIC cubic %.1f <= spline %.1f" : "auto: BIC cubic %.1f > spline %.1f",
               fit->cubic_fit.bic, fit->spline_fit.bic) +
        format(" (spline %.1f effective dof, knots every %.1f mm)", fit->spline_fit.dof, fit->knot_spacing_mm);
  } else {
    fit->selection = std::string("asked for: ") + to_string(options.model);
  }
  const bool use_spline = fit->model == ProfileEdgeModel::kSpline;
  fit->curve = use_spline ? spline.curve : fit->cubic;
  fit->rms_mm = use_spline ? fit->spline_fit.rms_mm : fit->cubic_fit.rms_mm;
  fit->max_mm = use_spline ? fit->spline_fit.max_mm : fit->cubic_fit.max_mm;
  if (use_spline && !fit->smoothing_converged && fit->spline_fit.rms_mm > 1.5 * std::sqrt(2.0) * sigma) {
    char text[300];
    std::snprintf(text, sizeof(text),
                  ": the spline's residual (RMS %.3f mm) stays above the noise (sigma %.3f mm) even with knots every "
                  "%.1f mm: the edge has detail finer than that (give a smaller knot spacing)",
                  fit->spline_fit.rms_mm, sigma, fit->knot_spacing_mm);
    fit->warnings.push_back(source + text);
  }
}

}  // namespace

bool ProfileEdgeFitOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!points.IsValid(&problem)) {
  } else if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) {
    problem = "noise_mm must be >= 0 (0: estimate it)";
  } else if (spline_control_points != 0 && spline_control_points < 4) {
    problem = "spline_control_points must be 0 (automatic) or at least 4";
  } else if (!(knot_spacing_mm >= 0.0) || !std::isfinite(knot_spacing_mm)) {
    problem = "knot_spacing_mm must be >= 0 (0: automatic)";
  } else if (!(outlier_threshold_sigma >= 2.0) || !std::isfinite(outlier_threshold_sigma)) {
    problem = "outlier_threshold_sigma must be at least 2";
  } else if (!(min_outlier_mm >= 0.0) || !std::isfinite(min_outlier_mm)) {
    problem = "min_outlier_mm must be >= 0";
  } else if (max_reweighting_passes < 1 || max_reweighting_passes > 100) {
    problem = "max_reweighting_passes must be in [1, 100]";
  } else if (!(max_outlier_fraction > 0.0 && max_outlier_fraction <= 0.5)) {
    problem = "max_outlier_fraction must be in (0, 0.5]";
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
  fit.points = check_profile_edge_points(points, options.points, source, options.noise_mm);
  fit.duplicates_dropped = fit.points.duplicates;
  const Prepared p = prepare(points, fit.points);
  // The median screen's residuals also give a sigma that many outliers cannot inflate (every third point a spike
  // spoils every second difference); a screen residual is ~1.08 times a curve's (a median of 5 carries ~0.56 sigma).
  const std::vector<double> screen = median_screen_residuals(p);
  const double screen_sigma = median_of(screen) / (1.08 * kRayleighMedian);
  // Taken only when it is far below the second-difference one (the smaller of two estimates is biased low).
  const bool spoiled = screen_sigma > 0.0 && screen_sigma < 0.7 * fit.points.noise_mm;
  fit.noise_mm = options.noise_mm > 0.0 ? options.noise_mm : spoiled ? screen_sigma : fit.points.noise_mm;
  const double sigma = fit.noise_mm;
  const auto cubic = [&](const std::vector<char>& inlier) {
    return fit_cubic(p, inlier, options.cubic_length_segments);
  };
  Reweighted robust;
  try {
    if (options.model == ProfileEdgeModel::kCubic) {
      robust = reweight(p, screen, sigma, options, cubic);
    } else {
      robust = robust_spline(p, screen, sigma, options, &fit);
    }
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  record_outliers(p, robust, source, options, &fit);

  const ModelFit cubic_fit = options.model == ProfileEdgeModel::kCubic ? robust.fit : cubic(robust.inlier);
  fit.cubic = cubic_fit.curve;
  fit.cubic_fit = residual_of(cubic_fit, p, robust.inlier);
  choose_model(options, robust.fit, sigma, source, &fit);
  return fit;
}

}  // namespace conform
