#pragma once
// The edge curve of a deformed profile, fitted to its measured edge points, with arc length from the profile's origin
// (Chen et al., LNG profiles).
//
//   cubic   the paper's model: one least-squares cubic C(t) over the chord-length parameter t in [0, 1] (Eq. 1-2).
//   spline  beyond the paper: a smoothing cubic B-spline over chord length (mm), its smoothing target 2 n sigma^2 for
//           sensor noise sigma (the noise across the edge; the parameters absorb the noise along it), which follows a
//           local kink that one global cubic over 12 m cannot.
//   auto    fits both and keeps the cubic unless its RMS residual exceeds the spline's by auto_ratio (a cubic that
//           only fits the noise has the spline's residual; one that misses a kink has many times it).
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
  static ProfileEdgeCurve cubic(PolynomialCurve curve, int length_segments = 256);
  static ProfileEdgeCurve spline(BSplineCurve curve);

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

 private:
  void tabulate(std::vector<double> breaks);
  std::size_t segment_of_length(double s_mm) const;

  ProfileEdgeModel model_ = ProfileEdgeModel::kCubic;
  PolynomialCurve polynomial_;
  BSplineCurve bspline_;
  std::vector<double> t_ = {0.0, 1.0};  // segment breaks
  std::vector<double> s_ = {0.0, 0.0};  // s(t_k)
};

struct ProfileEdgeFitOptions {
  ProfileEdgeModel model = ProfileEdgeModel::kAuto;
  ProfileEdgePointsOptions points;  // ordering, gap and count checks
  double noise_mm = 0.0;            // sensor noise sigma per coordinate, mm; 0: estimated from the points
  int spline_control_points = 0;    // 0: automatic (bspline_fit.h: clamp(n / 2, 8, 4000))
  double auto_ratio = 1.25;         // auto: spline when cubic RMS > auto_ratio * spline RMS (> 1)
  int cubic_length_segments = 256;  // arc-length table of the cubic (>= 1)

  bool IsValid(std::string* error) const;
};

struct ProfileEdgeResidual {
  bool fitted = false;
  double rms_mm = 0.0;  // of |P_i - C(t_i)|
  double max_mm = 0.0;
  int max_index = 0;  // the point with the largest residual
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
};

// Throws conform::Error (naming `source`) for invalid options or edge points that fail the checks of
// check_profile_edge_points, or when a fit is singular.
ProfileEdgeFit fit_profile_edge(const std::vector<Eigen::Vector3d>& points, const ProfileEdgeFitOptions& options,
                                const std::string& source = "edge points");

}  // namespace conform
