#pragma once
// The edge curve of a deformed profile, fitted to its measured edge points, with arc length from the profile's origin
// (Chen et al., LNG profiles).
//
//   cubic   the paper's model: one least-squares cubic C(t) over t in [0, 1] (Eq. 1-2).
//   spline  beyond the paper: a smoothing cubic B-spline (parameter in mm) with knots every knot_spacing_mm (tied to
//           the sampling step and the noise), its smoothing target 2 n sigma^2 for sensor noise sigma, which follows
//           a local kink that one global cubic over 12 m cannot.
//   auto    fits both on the same inliers and keeps the one with the lower BIC (Schwarz 1978),
//           n ln(RSS / n) + k ln(n), k = 12 for the cubic and 3 x the spline's effective degrees of freedom
//           (the trace of its smoother matrix): the spline must pay for its flexibility.
//
// Departures from the paper, for real scans (docs/profile.md): the parameter of each point is its projection on the
// main axis of the points (t_i of Eq. 2 uses chord length, which noise stretches: every noisy step adds to it);
// points are centred (the curve keeps an origin) so that shop coordinates far from the machine's origin lose no
// digits; duplicates are dropped; points out of order by less than the noise allows are sorted; outliers are
// rejected by iterative reweighting (weight 0 beyond outlier_threshold_sigma robust sigmas of the residuals, every
// pass re-deciding every point from the latest curve).
//
// Arc length s(t) = integral of |C'| from the start (Eq. 7) is tabulated once per span (spline) or per 1/256 of the
// cubic's parameter range, so that inverting it for many points costs one short quadrature each.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/compensation/profile_edge_points.h"
#include "conform/fitting/arc_length.h"
#include "conform/fitting/bspline_curve.h"
#include "conform/fitting/polynomial_curve.h"

namespace conform {

enum class ProfileEdgeModel { kAuto, kCubic, kSpline };

const char* to_string(ProfileEdgeModel model);
// "auto", "cubic" or "spline"; false for anything else.
bool parse_profile_edge_model(const std::string& text, ProfileEdgeModel* model);

// One edge model with its arc-length table: either a cubic over t in [0, 1] or a B-spline over chord length.
class ProfileEdgeCurve {
 public:
  ProfileEdgeCurve() = default;
  // The curve plus `origin` (the fits work in centred coordinates; position() adds the origin back).
  static ProfileEdgeCurve cubic(PolynomialCurve curve, int length_segments = 256,
                                const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());
  static ProfileEdgeCurve spline(BSplineCurve curve, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

  ProfileEdgeModel model() const { return model_; }
  double t_begin() const { return t_.front(); }
  double t_end() const { return t_.back(); }
  Eigen::Vector3d position(double t) const;
  Eigen::Vector3d derivative(double t, int order = 1) const;
  double speed(double t) const { return derivative(t, 1).norm(); }

  // s(t_end), mm: the measured edge length.
  double length_mm() const { return s_.back(); }
  // s(t) from t_begin, mm; t is clamped into the domain.
  double arc_length_at(double t) const;
  // The t with s(t) = s_mm, to tolerance_mm (Eq. 7). Throws conform::Error when s_mm lies outside [0, length_mm()].
  ArcLengthInverse parameter_at(double s_mm, double tolerance_mm = 1e-8) const;
  // A t with s(t) close to s_mm (linear in the table, clamped): a start for searches, not an answer.
  double approximate_parameter_at(double s_mm) const;

  const PolynomialCurve& polynomial() const { return polynomial_; }
  const BSplineCurve& bspline() const { return bspline_; }
  const Eigen::Vector3d& origin() const { return origin_; }

 private:
  void tabulate(std::vector<double> breaks);
  Eigen::Vector3d local_derivative(double t, int order) const;
  std::size_t segment_of_length(double s_mm) const;

  ProfileEdgeModel model_ = ProfileEdgeModel::kCubic;
  PolynomialCurve polynomial_;
  BSplineCurve bspline_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::vector<double> t_ = {0.0, 1.0};  // segment breaks
  std::vector<double> s_ = {0.0, 0.0};  // s(t_k)
};

struct ProfileEdgeFitOptions {
  ProfileEdgeModel model = ProfileEdgeModel::kAuto;
  ProfileEdgePointsOptions points;        // ordering, gap and count checks
  double noise_mm = 0.0;                  // sensor noise sigma per coordinate, mm; 0: estimated from the points
  int spline_control_points = 0;          // 0: from knot_spacing_mm
  double knot_spacing_mm = 0.0;           // spline knots, mm; 0: max(10 x median step, 250 sigma, 20 mm)
  double outlier_threshold_sigma = 6.0;   // a point further than this many robust sigmas from the curve is an outlier
  double min_outlier_mm = 0.1;            // residuals below this are never outliers, mm (noise-free data)
  int max_reweighting_passes = 12;        // of the outlier rejection (>= 1)
  double max_outlier_fraction = 0.2;      // more outliers than this: the scan is refused (in (0, 0.5])
  int cubic_length_segments = 256;        // arc-length table of the cubic (>= 1)

  bool IsValid(std::string* error) const;
};

struct ProfileEdgeResidual {
  bool fitted = false;
  double rms_mm = 0.0;  // of |P_i - C(t_i)| over the inliers
  double max_mm = 0.0;
  int max_index = 0;    // the inlier with the largest residual (index into the input points)
  double bic = 0.0;     // n ln(RSS / n) + k ln(n) over the 3 n inlier coordinates
  double dof = 0.0;     // k / 3: 4 for the cubic, the spline's effective degrees of freedom per coordinate
};

struct ProfileEdgeFit {
  ProfileEdgeCurve curve;  // the chosen model
  ProfileEdgeCurve cubic;  // the paper's cubic, always fitted (for the per-feature comparison)
  ProfileEdgeModel model = ProfileEdgeModel::kCubic;  // the chosen one, never kAuto
  std::string selection;                              // why that model
  ProfileEdgePointsCheck points;
  double noise_mm = 0.0;          // the sigma used for the spline's smoothing target (given or estimated)
  ProfileEdgeResidual cubic_fit;  // residuals of each fit made
  ProfileEdgeResidual spline_fit;
  double rms_mm = 0.0;  // of the chosen model
  double max_mm = 0.0;
  std::size_t duplicates_dropped = 0;  // points identical to the one before
  std::size_t outliers = 0;            // points rejected by the reweighting
  std::vector<int> outlier_indices;    // input indices of the first few outliers
  int reweighting_passes = 0;
  bool reweighting_converged = true;   // the inlier set stopped changing before max_reweighting_passes
  double knot_spacing_mm = 0.0;        // of the spline (0 when none was fitted)
  bool smoothing_converged = true;     // the spline met its smoothing target
  std::vector<std::string> warnings;   // things a user should look at (the fit is still used)
};

// Throws conform::Error (naming `source`) for invalid options or edge points that fail the checks of
// check_profile_edge_points, more outliers than max_outlier_fraction, or when a fit is singular.
ProfileEdgeFit fit_profile_edge(const std::vector<Eigen::Vector3d>& points, const ProfileEdgeFitOptions& options,
                                const std::string& source = "edge points");

}  // namespace conform
