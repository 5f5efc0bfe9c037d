#include "cylinder_shape.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "conform/core/constants.h"
#include "conform/core/median.h"
#include "cylinder_checks.h"

namespace conform::detail {
namespace {

constexpr int kBins = 72;          // 5 deg
constexpr std::size_t kMinBinPoints = 3;
constexpr int kTrimRounds = 8;
constexpr double kTrimSigmas = 3.0;
constexpr double kClosedShare = 0.9;
constexpr double kOffCentreShare = 0.05;
constexpr double kVisibleRelative = 1e-4;

std::string fixed(double v, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
  return buffer;
}

double azimuth(const Cylinder& model, const Eigen::Vector3d& e1, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p - model.axis_point;
  const Eigen::Vector3d e2 = model.axis_direction.cross(e1);
  return std::atan2(q.dot(e2), q.dot(e1));
}

Eigen::Matrix<double, 1, 5> harmonics(double theta) {
  Eigen::Matrix<double, 1, 5> row;
  row << 1.0, std::cos(theta), std::sin(theta), std::cos(2.0 * theta), std::sin(2.0 * theta);
  return row;
}

struct Bin {
  double theta = 0.0;  // centre
  double median_mm = 0.0;
  double weight = 0.0;  // sqrt(count)
};

// Weighted least squares of the harmonics through the kept bins (rank-revealing: a short arc leaves them collinear).
Eigen::Matrix<double, 5, 1> fit_harmonics(const std::vector<Bin>& bins, const std::vector<bool>& keep) {
  const Eigen::Index n = static_cast<Eigen::Index>(std::count(keep.begin(), keep.end(), true));
  Eigen::MatrixXd a(n, 5);
  Eigen::VectorXd b(n);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    if (!keep[i]) continue;
    a.row(row) = bins[i].weight * harmonics(bins[i].theta);
    b(row) = bins[i].weight * bins[i].median_mm;
    ++row;
  }
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solver(a);
  solver.setThreshold(1e-6);
  return solver.solve(b);
}

}  // namespace

double ShapeProfile::at(const Cylinder& model, const Eigen::Vector3d& p) const {
  return harmonics(azimuth(model, e1, p)) * coefficients;
}

Cylinder ShapeProfile::mean_circle(const Cylinder& model) const {
  Cylinder c = model;
  c.radius_mm += coefficients(0);
  c.axis_point += coefficients(1) * e1 + coefficients(2) * model.axis_direction.cross(e1);
  return c;
}

bool ShapeProfile::off_mean_circle() const {
  return closed && off_centre_mm > std::max(visible_mm, kOffCentreShare * max_abs_mm);
}

ShapeProfile shape_profile(const std::vector<Eigen::Vector3d>& points, const Cylinder& model, double threshold_mm,
                           double noise_mm) {
  ShapeProfile out;
  out.e1 = model.axis_direction.unitOrthogonal();
  std::vector<std::vector<double>> residuals(kBins);
  std::vector<int> bin_of(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double phi = azimuth(model, out.e1, points[i]) + kPi;  // [0, 2 pi]
    bin_of[i] = std::clamp(static_cast<int>(phi / kTwoPi * kBins), 0, kBins - 1);
    residuals[static_cast<std::size_t>(bin_of[i])].push_back(signed_distance(model, points[i]));
  }
  std::vector<Bin> bins;
  std::vector<int> index_of_bin(kBins, -1);
  for (int b = 0; b < kBins; ++b) {
    const std::vector<double>& r = residuals[static_cast<std::size_t>(b)];
    if (r.size() < kMinBinPoints) continue;
    index_of_bin[static_cast<std::size_t>(b)] = static_cast<int>(bins.size());
    bins.push_back({(b + 0.5) * kTwoPi / kBins - kPi, median(r), std::sqrt(static_cast<double>(r.size()))});
  }
  out.occupied_bins = static_cast<int>(bins.size());
  if (bins.size() < 6) return out;
  // Trimmed fit: bins whose median the smooth profile misses by more than 3 robust sigmas of the misfits (a seam
  // ridge, a dent) are left out, and the profile is fitted again to the rest.
  std::vector<bool> keep(bins.size(), true);
  for (int round = 0; round < kTrimRounds; ++round) {
    out.coefficients = fit_harmonics(bins, keep);
    std::vector<double> misfit(bins.size());
    std::vector<double> kept_misfit;
    for (std::size_t i = 0; i < bins.size(); ++i) {
      misfit[i] = bins[i].median_mm - harmonics(bins[i].theta) * out.coefficients;
      if (keep[i]) kept_misfit.push_back(misfit[i]);
    }
    const double tolerance = std::max(kTrimSigmas * robust_sigma(kept_misfit), noise_mm);
    std::vector<bool> next(bins.size());
    for (std::size_t i = 0; i < bins.size(); ++i) next[i] = std::abs(misfit[i]) <= tolerance;
    if (next == keep || std::count(next.begin(), next.end(), true) < 6) break;
    keep = next;
  }
  int kept = 0, cut = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    if (!keep[i]) continue;
    const double s = std::abs(harmonics(bins[i].theta) * out.coefficients);
    out.max_abs_mm = std::max(out.max_abs_mm, s);
    ++kept;
    cut += s > threshold_mm ? 1 : 0;
  }
  out.trimmed_bins = out.occupied_bins - kept;
  out.cut_off_share = kept > 0 ? static_cast<double>(cut) / kept : 0.0;
  std::vector<double> about_profile;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int b = index_of_bin[static_cast<std::size_t>(bin_of[i])];
    if (b < 0 || !keep[static_cast<std::size_t>(b)]) continue;
    about_profile.push_back(signed_distance(model, points[i]) - out.at(model, points[i]));
  }
  out.sheet_sigma_mm = robust_sigma(std::move(about_profile));
  out.closed = out.occupied_bins >= kClosedShare * kBins;
  out.off_centre_mm = out.coefficients.segment<2>(1).norm();
  const double per_bin = static_cast<double>(points.size()) / std::max(1, out.occupied_bins);
  out.visible_mm = std::max(3.0 * out.sheet_sigma_mm / std::sqrt(per_bin), kVisibleRelative * model.radius_mm);
  return out;
}

ShapeAmbiguity shape_ambiguity(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& inliers,
                               const Cylinder& model, double visible_mm, double shape_mm) {
  ShapeAmbiguity out;
  if (inliers.size() < 6) return out;
  const Eigen::Vector3d e1 = model.axis_direction.unitOrthogonal();
  std::vector<double> theta;
  theta.reserve(inliers.size());
  Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
  for (int i : inliers) {
    theta.push_back(azimuth(model, e1, points[static_cast<std::size_t>(i)]));
    const Eigen::Vector3d j(1.0, std::cos(theta.back()), std::sin(theta.back()));
    jtj.noalias() += j * j.transpose();
  }
  const Eigen::LDLT<Eigen::Matrix3d> normal_equations(jtj);
  constexpr int kPhases = 16;
  for (int k = 0; k < kPhases; ++k) {
    const double theta0 = kPi * k / kPhases;
    Eigen::Vector3d jtv = Eigen::Vector3d::Zero();
    for (double t : theta) jtv += Eigen::Vector3d(1.0, std::cos(t), std::sin(t)) * std::cos(2.0 * (t - theta0));
    const Eigen::Vector3d shift = normal_equations.solve(jtv);  // (radius, centre along e1, e2) per mm of a
    double remainder = 0.0;
    for (double t : theta) {
      const double absorbed = shift(0) + shift(1) * std::cos(t) + shift(2) * std::sin(t);
      remainder = std::max(remainder, std::abs(std::cos(2.0 * (t - theta0)) - absorbed));
    }
    if (!shift.allFinite() || !(remainder > 1e-9)) continue;
    const double hidden = std::max(visible_mm, shape_mm) / remainder;
    const double axis = hidden * shift.tail<2>().norm();
    if (axis > out.axis_mm) out = {hidden, axis, hidden * std::abs(shift(0))};
  }
  return out;
}

void judge_shape_ambiguity(const std::vector<Eigen::Vector3d>& points, const ShapeProfile& shape,
                           const Cylinder& centred_model, double max_mm, CylinderFitResult& r) {
  const ShapeAmbiguity a =
      shape_ambiguity(points, r.inliers, centred_model, shape.visible_mm, shape.max_abs_mm);
  r.hidden_ovality_mm = a.hidden_ovality_mm;
  r.shape_axis_ambiguity_mm = a.axis_mm;
  r.shape_radius_ambiguity_mm = a.radius_mm;
  if (std::max(a.axis_mm, a.radius_mm) > max_mm) {
    r.warnings.push_back("over a " + fixed(r.arc_rad * 180.0 / kPi, 1) + " deg arc an oval section cannot be told from a "
                         "round one: an ovality of " + fixed(a.hidden_ovality_mm, 3) + " mm (r = R + a cos 2 theta) "
                         "would leave no more trace in these residuals yet move the axis by up to " +
                         fixed(a.axis_mm, 3) + " mm and the radius by up to " + fixed(a.radius_mm, 3) +
                         " mm from the tube's mean circle; scan more of the circumference (a closed turn pins it)");
  }
}

}  // namespace conform::detail
