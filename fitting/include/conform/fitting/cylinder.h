#pragma once
// A circular cylinder fitted to a scan of a tube (outer or inner wall, the full turn or a partial arc):
//   1. RANSAC on points with normals: two points and their normals per sample (axis n1 x n2, centre where the normal
//      lines cross, radius from both points), scored by MSAC on a seeded subset; a point agrees with a hypothesis
//      when it is within the threshold of the surface and its normal within the angle of the surface normal.
//   2. Geometric least squares (Ceres, Levenberg-Marquardt) over all inliers: residual |(p - c) x a| - r (the
//      distance to the surface, unbiased under noise, unlike the algebraic d^2 - r^2), the axis a on the unit sphere
//      (ceres::SphereManifold), the axis point c in the plane through the centroid across the axis, a Huber loss
//      scaled to the noise sigma estimated from the residuals (1.4826 MAD).
//   3. Inliers re-selected against the refined model (|residual| <= threshold) and refined again, until the inlier
//      set stops changing.
// Coordinates are centred on the points' centroid and computed in double.
//
// A result says whether the data define a cylinder at all: a plane (no measurable curvature over the scanned arc), a
// sphere-like blob (a sphere explains the points far better), too few inliers, a radius pinned at a bound or an axis
// outside the prior are failures with a reason, never silent answers.

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cloud.h"
#include "conform/core/progress.h"

namespace conform {

struct Cylinder {
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();       // mm, a point on the axis
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();  // unit
  double radius_mm = 0.0;
};

// |(p - c) x a| - r: the distance of p from the surface, positive outside (away from the axis), mm.
double signed_distance(const Cylinder& cylinder, const Eigen::Vector3d& p);

enum class CylinderFailure {
  kNone,
  kNoConsensus,       // no hypothesis, or too few inliers (below min_inlier_fraction)
  kPlane,             // the scanned arc is flat to within the noise: no radius to measure
  kSphere,            // a sphere explains the points much better than a cylinder
  kRadiusAtBound,     // the best radius lies on min_radius_mm or max_radius_mm
  kAxisOutsidePrior,  // the refined axis left the cone around axis_prior
  kNotConverged,      // the least-squares solver stopped before its tolerances
};

// "none", "no consensus", "plane", "sphere", "radius at bound", "axis outside prior", "not converged".
const char* to_string(CylinderFailure failure);

// Which side of the wall the normals show: away from the axis (outer), towards it (inner), or mixed / unoriented.
enum class CylinderSide { kUnknown, kOuter, kInner };
const char* to_string(CylinderSide side);

struct CylinderFitOptions {
  // --- inliers ---
  double threshold_mm = 0.0;   // |distance to the surface| of an inlier, mm; 0: automatic (inlier_sigmas noise sigmas)
  double inlier_sigmas = 3.0;  // the automatic threshold, in noise sigmas (1.4826 MAD of the residuals)
  double normal_threshold_rad = 0.5236;  // RANSAC: largest angle between a point's normal and the surface's (30 deg)

  // --- what the cylinder may be ---
  double min_radius_mm = 0.0;
  double max_radius_mm = std::numeric_limits<double>::infinity();
  Eigen::Vector3d axis_prior = Eigen::Vector3d::Zero();   // expected axis direction (sign ignored); zero: none
  double axis_prior_tolerance_rad = 0.17453292519943295;  // largest angle from the prior, rad (10 deg)

  // --- RANSAC ---
  int ransac_max_iterations = 2000;            // hypotheses at most
  int ransac_min_iterations = 100;             // hypotheses at least (noisy normals make good samples rarer than w^2)
  double ransac_confidence = 0.999;            // stop when a better model is this unlikely to be missed
  int ransac_sample_points = 4000;             // hypotheses are scored on a seeded subset of at most this many points
  double min_normal_angle_rad = 0.0872664626;  // a sample's normals must differ by this much (5 deg) to give an axis
  std::uint64_t seed = 1;                      // the same points, options and seed give the same bytes out

  // --- least squares ---
  int refine_rounds = 6;            // re-selection + refinement rounds at most
  double loss_sigmas = 2.0;         // Huber loss scale, in noise sigmas
  int max_solver_iterations = 100;  // Levenberg-Marquardt iterations per round
  double solver_tolerance = 1e-12;  // Ceres function, gradient and parameter tolerances

  // --- acceptance ---
  double min_inlier_fraction = 0.2;  // fewer inliers than this share of the points: kNoConsensus
  double min_sagitta_sigmas = 3.0;   // the arc's depth r (1 - cos(arc / 2)) must exceed this many noise sigmas
  double sphere_ratio = 0.5;         // kSphere when a sphere's median |residual| is below this share of the cylinder's
  double max_shape_ambiguity_mm = 0.05;  // warn when an ovality the residuals cannot show would move the axis or
                                        // the radius by more than this (CylinderFitResult::shape_axis_ambiguity_mm)

  int normal_neighbors = 16;  // k of the PCA normals estimated when the input has none (core/normals.h)
  ProgressFn progress;        // stages "cylinder: normals", "cylinder: ransac", "cylinder: refine"

  // False (and why, naming the option) for a value out of range or non-finite.
  bool IsValid(std::string* error) const;
};

struct CylinderFitResult {
  Cylinder cylinder;       // axis_point: the point of the axis nearest the inliers' centroid; direction: its largest
                           // component positive (or along axis_prior when one is given)
  bool ok = false;         // a cylinder that passed every check; otherwise `failure` and `termination` say why
  bool converged = false;  // the last least-squares round met its tolerances
  CylinderFailure failure = CylinderFailure::kNotConverged;
  std::string termination = "not run";  // "ok", or what went wrong in words a user can act on

  std::vector<int> inliers;  // indices into the input, ascending
  double inlier_fraction = 0.0;
  double rms_mm = 0.0;          // RMS of the inliers' distances to the surface
  double noise_sigma_mm = 0.0;  // 1.4826 MAD of the residuals of the points near the surface
  double threshold_mm = 0.0;    // the inlier threshold used last (given, or automatic)
  double arc_rad = 0.0;         // angular span of the inliers about the axis (2 pi: the full turn)
  CylinderSide side = CylinderSide::kUnknown;

  // Covariance of (tilt of the axis towards e1, towards e2 [rad], shift of the axis point along e1, e2 [mm], radius
  // [mm]) with (e1, e2, axis) = covariance_frame's columns: sigma^2 (J^T J)^-1 at the solution over the inliers,
  // sigma^2 = sum of squared residuals / (inliers - 5). It assumes independent noise; a systematic deviation (ovality)
  // is not noise and the figures then only say how well the data pin the best-fitting cylinder.
  Eigen::Matrix<double, 5, 5> covariance = Eigen::Matrix<double, 5, 5>::Zero();
  Eigen::Matrix3d covariance_frame = Eigen::Matrix3d::Identity();
  double radius_std_mm = 0.0;       // sqrt of the radius variance
  double axis_angle_std_rad = 0.0;  // sqrt of the largest eigenvalue of the tilt block
  double axis_point_std_mm = 0.0;   // sqrt of the largest eigenvalue of the axis-point block

  // The cross-section's systematic deviation from the fitted circle: the largest |median residual| over the scanned
  // azimuth of a smooth profile (harmonics 0-2 of the azimuth, fitted to 5 deg bins; a narrow seam ridge and outliers
  // left out). On a full oval tube about the ovality amplitude a (r = R + a cos 2 theta); ~0 on a round one.
  double shape_deviation_mm = 0.0;
  // What a partial arc cannot tell (an oval section fits a circle over a short arc with the centre and radius moved):
  // the largest ovality a the residuals would not show (or the one they show, if larger), and how far it would move
  // the axis and the radius from the tube's mean circle (worst phase). 0 over the full turn.
  double hidden_ovality_mm = 0.0;
  double shape_axis_ambiguity_mm = 0.0;
  double shape_radius_ambiguity_mm = 0.0;
  // What the fit found doubtful without failing (e.g. a band that cuts off a systematic deviation), in words a user
  // can act on; empty when there is nothing to say.
  std::vector<std::string> warnings;

  double plane_rms_mm = 0.0;        // a plane through the inliers (PCA): what the curvature must beat
  double sphere_median_mm = 0.0;    // median |residual| of the best algebraic sphere through all points
  double cylinder_median_mm = 0.0;  // median |residual| of all points to the cylinder
  int ransac_iterations = 0;        // hypotheses drawn
  int refine_rounds = 0;            // least-squares rounds run
  int solver_iterations = 0;        // Levenberg-Marquardt iterations over all rounds
};

// Fits a cylinder to points with normals (one unit normal per point; the sign of a normal does not matter, its
// direction does). Throws conform::Error when the options are not valid, a point or normal is not finite, the counts
// differ, there are fewer than 6 points (the model has 5 degrees of freedom), all points coincide, or all lie on a
// line. A plane, a sphere, too few inliers and the other CylinderFailure cases come back as a result with ok false.
CylinderFitResult fit_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                               const CylinderFitOptions& options);

// The same on a cloud; its normals are used when it has them, PCA normals (options.normal_neighbors) otherwise (and
// then `side` is kUnknown: their signs say nothing about the wall).
CylinderFitResult fit_cylinder(const Cloud& cloud, const CylinderFitOptions& options);

}  // namespace conform
