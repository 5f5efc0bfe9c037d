#pragma once
// Form of a measured feature (issue 33): the least-squares plane through points, and the width of the zone that holds
// a feature's residuals. ISO 1101 defines flatness, cylindricity and sphericity as the minimum-zone width (two
// parallel planes, two coaxial cylinders, two concentric spheres); the zone here is about the least-squares feature,
// which is never narrower than the minimum zone and, for a form error much larger than the noise, close to it
// (docs/inspect.md). A scan's isolated outliers would set a min-max width alone, so the width is also given after a
// stated trim.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct PlaneFit {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // the points' centroid, on the plane, mm
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit; the sign is arbitrary (the caller orients it)
  double rms_mm = 0.0;                                // RMS of the orthogonal residuals
  // The plane is determined: at least 3 points whose second-smallest spread (covariance eigenvalue) is more than
  // 1e-12 of the largest (not all on a line).
  bool ok = false;
};

// The plane minimising the sum of squared orthogonal distances: through the centroid, normal along the covariance's
// smallest eigenvector (Pearson 1901), accumulated in double relative to the centroid. Fewer than 3 points: ok false.
PlaneFit fit_plane(const std::vector<Eigen::Vector3d>& points);

struct SphereFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // mm
  double radius_mm = 0.0;
  double rms_mm = 0.0;  // RMS of |p - centre| - radius
  bool ok = false;      // at least 4 points, not on a plane or a circle, and Gauss-Newton converged
};

// The sphere minimising the sum of squared distances |p - c| - r: the algebraic fit (|p|^2 = 2 c.p + k, linear least
// squares; Kasa 1976) as the start, then Gauss-Newton on the geometric residuals until a step moves the centre and
// radius by less than 1e-12 of the radius (at most 50 steps). Relative to the centroid, in double.
SphereFit fit_sphere(const std::vector<Eigen::Vector3d>& points);

struct FormZone {
  double width_mm = 0.0;       // upper minus lower trimmed residual (the percentiles below)
  double lower_mm = 0.0;       // the trim_share / 2 percentile of the residuals
  double upper_mm = 0.0;       // the 1 - trim_share / 2 percentile
  double full_width_mm = 0.0;  // max minus min, no trim
  double trim_share = 0.0;     // as used
  std::size_t count = 0;
};

// The zone of signed residuals (mm, NaN left out): its width with `trim_share` of them left out, half at each end
// (percentiles by linear interpolation between ranks, evaluation/statistics.h), and without. trim_share in [0, 0.5).
// All zeros for no finite residual.
FormZone form_zone(const std::vector<double>& residuals_mm, double trim_share);

}  // namespace conform
