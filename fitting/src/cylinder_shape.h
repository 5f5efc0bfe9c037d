#pragma once
// The cross-section's systematic deviation from a fitted circle (private to the fitting module): the median residual
// in azimuth bins, and a smooth low-order profile through them that a narrow seam ridge or outliers cannot bend.
//
// Why: an inlier band set by the noise (3 sigmas) can cut off a smooth deviation of the shape (an oval tube: the
// radius varies by +-a round the turn, a >> sigma). The band then keeps the part of the tube a circle hugs, and the
// re-selection rounds settle on that self-consistent subset: a closed tube reported as a 230 deg arc, its axis off by
// a sizeable share of a. The profile shows what the band cut off: the surface's median residual lies outside the band
// over a wide share of the azimuth, smoothly, not over a seam's few degrees.

#include <vector>

#include <Eigen/Core>

#include "conform/fitting/cylinder.h"

namespace conform::detail {

struct ShapeProfile {
  // The smooth profile s(theta) = c0 + c1 cos(theta) + s1 sin(theta) + c2 cos(2 theta) + s2 sin(2 theta), theta the
  // azimuth about the model's axis from `e1` towards axis x e1, fitted to the bins' median residuals (weights: the
  // bins' point counts); bins the fit trims (a seam ridge, a dent) do not bend it.
  Eigen::Matrix<double, 5, 1> coefficients = Eigen::Matrix<double, 5, 1>::Zero();
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX();
  int occupied_bins = 0;     // bins with enough points to take a median
  int trimmed_bins = 0;      // occupied bins the smooth profile leaves out
  double max_abs_mm = 0.0;   // max |s| over the kept bins: the systematic deviation from the circle
  double cut_off_share = 0.0;  // share of the kept bins where |s| exceeds the threshold: what the band cut off
  double sheet_sigma_mm = 0.0;  // 1.4826 MAD of the points' residuals about s (kept bins): the noise about the shape

  bool closed = false;         // the points cover at least 90% of the bins: the full turn, where the harmonics are
                               // orthogonal and harmonics 0 and 1 of s say how far the circle is from the mean one
  double off_centre_mm = 0.0;  // |(c1, s1)|: the centre's offset from the profile's least-squares reference circle
  double visible_mm = 0.0;     // the smallest systematic residual the bins show: 3 standard errors of a bin's
                               // median (sheet sigma / sqrt(points per bin)), and no less than 1e-4 R

  // s at the azimuth of p (mm).
  double at(const Cylinder& model, const Eigen::Vector3d& p) const;
  // On a closed turn: the model moved to the least-squares reference circle of roundness metrology (the radius by c0,
  // the centre by c1 e1 + s1 e2: to first order a circle moved by (dx, dy) changes the residuals by dx cos + dy sin).
  Cylinder mean_circle(const Cylinder& model) const;
  // A closed turn whose circle is off the mean one by more than visible_mm and 5% of max_abs_mm.
  bool off_mean_circle() const;
};

// The profile of the signed residuals of `points` (all of them: the bins' medians shrug off outliers) against
// `model`, with `threshold_mm` the inlier band it is judged against and `noise_mm` the noise sigma, the least misfit
// of a bin's median the trimming tolerates. Bins are 5 deg wide; a bin needs 3 points.
ShapeProfile shape_profile(const std::vector<Eigen::Vector3d>& points, const Cylinder& model, double threshold_mm,
                           double noise_mm);

struct ShapeAmbiguity {
  double hidden_ovality_mm = 0.0;  // the largest ovality a (worst phase) the residuals would not show, or the one
                                   // they do show when larger
  double axis_mm = 0.0;            // how far that ovality moves the fitted axis (worst phase)
  double radius_mm = 0.0;          // and the fitted radius
};

// What a partial arc cannot tell: an oval section r = R + a cos 2(theta - theta0) fitted by a circle over the inliers'
// azimuths moves the circle's centre and radius by the least-squares projection of a cos 2(theta - theta0) onto the
// circle's derivatives (1, cos theta, sin theta), and leaves only the remainder visible in the residuals. Over the
// full turn the projection is zero (cos 2 theta is orthogonal to them); over a short arc the circle absorbs nearly all
// of it. With `visible_mm` the smallest systematic residual the data would show and `shape_mm` the one they show,
// the ovality that could hide is max(visible, shape) / (peak remainder per mm of a); ambiguity = its effect. Worst
// case over 16 phases theta0 (first order in a / R).
ShapeAmbiguity shape_ambiguity(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& inliers,
                               const Cylinder& model, double visible_mm, double shape_mm);

// Fills r's hidden_ovality_mm and shape_*_ambiguity_mm for the fit over r.inliers (centred points and model) and
// warns when the axis or radius ambiguity exceeds max_mm. The smallest systematic residual the data would show:
// 3 standard errors of a 5 deg bin's median, and no less than 1e-4 R.
void judge_shape_ambiguity(const std::vector<Eigen::Vector3d>& points, const ShapeProfile& shape,
                           const Cylinder& centred_model, double max_mm, CylinderFitResult& r);

}  // namespace conform::detail
