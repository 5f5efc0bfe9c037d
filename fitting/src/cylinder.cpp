#include "conform/fitting/cylinder.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/normals.h"
#include "cylinder_checks.h"
#include "cylinder_ransac.h"
#include "cylinder_refine.h"
#include "cylinder_shape.h"

namespace conform {
namespace {

// Below this share of the bounding-box diagonal a length counts as zero (noise-free data, degenerate spreads).
constexpr double kRelativeFloor = 1e-9;

struct Centred {
  std::vector<Eigen::Vector3d> points;   // minus the centroid
  std::vector<Eigen::Vector3d> normals;  // unit
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double extent_mm = 0.0;  // bounding-box diagonal
};

std::string count_text(std::size_t n, const char* what) { return std::to_string(n) + " " + what; }

void check_points(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 6) {
    throw Error("fit_cylinder: " + count_text(points.size(), "points") +
                "; a cylinder has 5 degrees of freedom and needs at least 6");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error("fit_cylinder: point " + std::to_string(i) + " is not finite");
  }
}

// Centres the points and checks that they span more than a line (Error otherwise).
Centred centre(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals) {
  check_points(points);
  if (normals.size() != points.size()) {
    throw Error("fit_cylinder: " + count_text(points.size(), "points") + " but " +
                count_text(normals.size(), "normals"));
  }
  Centred c;
  for (const auto& p : points) c.centroid += p;
  c.centroid /= static_cast<double>(points.size());
  Eigen::Vector3d lo = points.front(), hi = points.front();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  c.points.reserve(points.size());
  c.normals.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double length = normals[i].norm();
    if (!normals[i].allFinite() || !(length > 0.0)) {
      throw Error("fit_cylinder: normal " + std::to_string(i) + " is zero or not finite");
    }
    c.points.push_back(points[i] - c.centroid);
    c.normals.push_back(normals[i] / length);
    scatter.noalias() += c.points.back() * c.points.back().transpose();
    lo = lo.cwiseMin(points[i]);
    hi = hi.cwiseMax(points[i]);
  }
  c.extent_mm = (hi - lo).norm();
  const Eigen::Vector3d lambda =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(c.extent_mm > 0.0)) throw Error("fit_cylinder: all " + count_text(points.size(), "points coincide"));
  if (lambda(1) <= 1e-12 * lambda(2)) {
    throw Error("fit_cylinder: all " + count_text(points.size(), "points") +
                " lie on a line; a line defines no cylinder");
  }
  return c;
}

detail::RansacSettings ransac_settings(const CylinderFitOptions& o, double threshold_mm) {
  detail::RansacSettings s;
  s.threshold_mm = threshold_mm;
  s.cos_normal = std::cos(o.normal_threshold_rad);
  s.min_radius_mm = o.min_radius_mm;
  s.max_radius_mm = o.max_radius_mm;
  if (o.axis_prior.norm() > 0.0) {
    s.axis_prior = o.axis_prior.normalized();
    s.cos_prior = std::cos(o.axis_prior_tolerance_rad);
  }
  s.sin_min_normal_angle = std::sin(o.min_normal_angle_rad);
  s.max_iterations = o.ransac_max_iterations;
  s.min_iterations = o.ransac_min_iterations;
  s.confidence = o.ransac_confidence;
  s.sample_points = o.ransac_sample_points;
  s.seed = o.seed;
  return s;
}

std::vector<double> distances(const std::vector<Eigen::Vector3d>& points, const Cylinder& model) {
  std::vector<double> d(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) d[i] = signed_distance(model, points[i]);
  return d;
}

// Relative tolerance of the rounds before the inlier set settles (the last round uses the options' tolerance).
constexpr double kRoundTolerance = 1e-6;

// A radius this many bounding-box diagonals long bends the scan by less than 1/8000 of its size: a plane.
constexpr double kFlatRadius = 1e3;

bool at_bound(double radius, const CylinderFitOptions& o) {
  return (o.min_radius_mm > 0.0 && radius <= o.min_radius_mm * (1.0 + 1e-9)) ||
         (std::isfinite(o.max_radius_mm) && radius >= o.max_radius_mm * (1.0 - 1e-9));
}

struct Rounds {
  Cylinder model;
  std::vector<int> inliers;
  double sigma = 0.0;
  double threshold = 0.0;
  bool converged = false;
  std::string message;
  int rounds = 0;
  int iterations = 0;
};

// Refine on the inliers, re-select them against the refined model, until the set stops changing. The noise sigma is
// the MAD of the residuals within three thresholds of the surface: outliers far off do not inflate it, and a
// systematic deviation wider than the first threshold (an oval tube) widens the next one until the tube is in.
// While the set still moves, a round solves to kRoundTolerance only; once it holds still, one more round solves to
// the options' tight tolerance and must leave it unchanged too.
// min_threshold_mm: the automatic threshold never drops below it (the widening of a cut-off shape, below).
Rounds refine_in_rounds(const Centred& data, const Cylinder& start, std::vector<int> start_inliers, double threshold,
                        double min_threshold_mm, const CylinderFitOptions& o) {
  const double floor = std::max(kRelativeFloor * data.extent_mm, min_threshold_mm);
  Rounds out;
  out.model = start;
  out.inliers = std::move(start_inliers);
  out.threshold = threshold;
  std::vector<double> first;
  for (int i : out.inliers) first.push_back(signed_distance(out.model, data.points[static_cast<std::size_t>(i)]));
  out.sigma = detail::robust_sigma(std::move(first));
  bool tight = false;
  for (int round = 0; round < o.refine_rounds && out.inliers.size() >= 6; ++round) {
    tight = tight || round + 1 == o.refine_rounds;
    const double tolerance = tight ? o.solver_tolerance : std::max(o.solver_tolerance, kRoundTolerance);
    const detail::RefineSettings settings{o.loss_sigmas * std::max(out.sigma, floor), o.min_radius_mm, o.max_radius_mm,
                                          o.max_solver_iterations, tolerance};
    const detail::RefineOutcome refined = detail::refine_cylinder(data.points, out.inliers, out.model, settings);
    out.model = refined.model;
    out.converged = refined.converged;
    out.message = refined.message;
    out.iterations += refined.iterations;
    ++out.rounds;
    const std::vector<double> d = distances(data.points, out.model);
    std::vector<double> near;
    for (double v : d) {
      if (std::abs(v) <= 3.0 * out.threshold) near.push_back(v);
    }
    out.sigma = detail::robust_sigma(std::move(near));
    out.threshold = o.threshold_mm > 0.0 ? o.threshold_mm : std::max(o.inlier_sigmas * out.sigma, floor);
    std::vector<int> selected;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (std::abs(d[i]) <= out.threshold) selected.push_back(static_cast<int>(i));
    }
    const bool stable = selected == out.inliers;
    out.inliers = std::move(selected);
    // Nothing later rounds could change: the radius is pinned on a bound, or has run off towards a plane's infinity.
    const bool flat = !(out.model.radius_mm < kFlatRadius * data.extent_mm);
    if ((stable && tight) || at_bound(out.model.radius_mm, o) || flat) break;
    tight = stable;
  }
  return out;
}

std::string fixed(double v, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
  return buffer;
}

// A deviation that the band cuts off over more than this share of the azimuth is the shape's, not a seam's.
constexpr double kCutOffShare = 0.1;
constexpr int kWidenPasses = 4;

// The self-check of the rounds' answer: where the surface's median residual lies outside the inlier band over a wide
// share of the azimuth, smoothly (cylinder_shape.h), the band has cut off a systematic deviation of the shape (an oval
// tube) and the rounds settled on the part a circle hugs. Widen the band to the smooth deviation plus the noise
// about it, restart from the points on that smooth sheet (a seam ridge and outliers stay off it), refine again, and
// repeat while the band moves. A given threshold is kept; a band still cutting off the shape is then a warning.
detail::ShapeProfile widen_cut_off_shape(const Centred& data, Rounds& rounds, const CylinderFitOptions& o,
                                         CylinderFitResult& result) {
  detail::ShapeProfile shape = detail::shape_profile(data.points, rounds.model, rounds.threshold, rounds.sigma);
  const auto cut = [](const detail::ShapeProfile& s) { return s.cut_off_share > kCutOffShare; };
  for (int pass = 0; pass < kWidenPasses && o.threshold_mm <= 0.0 && (cut(shape) || shape.off_mean_circle()); ++pass) {
    // A closed turn: start from the roundness reference circle of the profile (harmonics 0 and 1 moved into the
    // radius and the centre), whose basin the refinement then stays in.
    const Cylinder start = shape.closed ? shape.mean_circle(rounds.model) : rounds.model;
    const detail::ShapeProfile about =
        shape.closed ? detail::shape_profile(data.points, start, rounds.threshold, rounds.sigma) : shape;
    const double band = about.max_abs_mm + o.inlier_sigmas * about.sheet_sigma_mm;
    const double sheet_band = std::max(rounds.threshold, o.inlier_sigmas * about.sheet_sigma_mm);
    std::vector<int> sheet;
    for (std::size_t i = 0; i < data.points.size(); ++i) {
      const Eigen::Vector3d& p = data.points[i];
      if (std::abs(signed_distance(start, p) - about.at(start, p)) <= sheet_band) sheet.push_back(static_cast<int>(i));
    }
    const int earlier_rounds = rounds.rounds, earlier_iterations = rounds.iterations;
    rounds = refine_in_rounds(data, start, std::move(sheet), band, band, o);
    rounds.rounds += earlier_rounds;
    rounds.iterations += earlier_iterations;
    shape = detail::shape_profile(data.points, rounds.model, rounds.threshold, rounds.sigma);
  }
  if (cut(shape)) {
    const double needed = shape.max_abs_mm + o.inlier_sigmas * shape.sheet_sigma_mm;
    result.warnings.push_back(
        "the inlier band (" + fixed(rounds.threshold, 4) + " mm) cuts off a systematic deviation of the cross-section " +
        "of up to " + fixed(shape.max_abs_mm, 4) + " mm (ovality?) over " + fixed(100.0 * shape.cut_off_share, 0) +
        "% of the scanned azimuth: the cylinder fits part of the tube only, its axis and radius are not the tube's " +
        "mean circle; " +
        (o.threshold_mm > 0.0 ? "raise --threshold to " + fixed(needed, 3) + " mm or use 0 (automatic)"
                              : "the automatic band did not settle: check the scan for a deformation"));
  } else if (shape.off_mean_circle()) {
    result.warnings.push_back("the residuals of this closed tube are off-centre by " + fixed(shape.off_centre_mm, 4) +
                              " mm (their first harmonic): the fitted axis is not the mean circle's; check the scan "
                              "for a deformation the fit cannot follow");
  }
  return shape;
}

void fail(CylinderFitResult& r, CylinderFailure failure, std::string why) {
  r.ok = false;
  r.failure = failure;
  r.termination = std::move(why);
}

// The checks of a refined cylinder, in the order a user most needs to hear about them.
void judge(CylinderFitResult& r, const Rounds& rounds, const CylinderFitOptions& o, double floor) {
  const double radius = r.cylinder.radius_mm;
  const double sigma = std::max(r.noise_sigma_mm, floor);
  const double sagitta = radius * (1.0 - std::cos(std::min(r.arc_rad, kPi) / 2.0));
  const double angle_to_prior =
      o.axis_prior.norm() > 0.0
          ? std::acos(std::min(1.0, std::abs(r.cylinder.axis_direction.dot(o.axis_prior.normalized()))))
          : 0.0;
  r.ok = true;
  r.failure = CylinderFailure::kNone;
  r.termination = "ok";
  if (!std::isfinite(radius) || !r.cylinder.axis_point.allFinite() || !r.cylinder.axis_direction.allFinite()) {
    fail(r, CylinderFailure::kNotConverged, "not a cylinder: the least-squares solve diverged");
  } else if (!(sagitta > o.min_sagitta_sigmas * sigma)) {
    fail(r, CylinderFailure::kPlane,
         "not a cylinder: the inliers span " + fixed(r.arc_rad * 180.0 / kPi, 3) + " deg of a radius " +
             fixed(radius, 3) + " mm arc, only " + fixed(sagitta, 4) + " mm deep against a noise sigma of " +
             fixed(sigma, 4) + " mm: the points lie on a plane (or too shallow an arc to measure a radius)");
  } else if (r.sphere_median_mm < o.sphere_ratio * r.cylinder_median_mm) {
    fail(r, CylinderFailure::kSphere,
         "not a cylinder: a sphere fits the points better (median |residual| " + fixed(r.sphere_median_mm, 4) +
             " mm against " + fixed(r.cylinder_median_mm, 4) + " mm for the best cylinder)");
  } else if (at_bound(radius, o)) {
    fail(r, CylinderFailure::kRadiusAtBound,
         "the best radius lies on a bound (" + fixed(radius, 4) + " mm): widen --min-radius/--max-radius");
  } else if (r.inlier_fraction < o.min_inlier_fraction) {
    fail(r, CylinderFailure::kNoConsensus,
         "not a cylinder: only " + fixed(100.0 * r.inlier_fraction, 1) + "% of the points are within " +
             fixed(r.threshold_mm, 4) + " mm of the best cylinder (at least " +
             fixed(100.0 * o.min_inlier_fraction, 1) + "% needed)");
  } else if (angle_to_prior > o.axis_prior_tolerance_rad) {
    fail(r, CylinderFailure::kAxisOutsidePrior,
         "the refined axis is " + fixed(angle_to_prior * 180.0 / kPi, 3) + " deg from the axis prior (tolerance " +
             fixed(o.axis_prior_tolerance_rad * 180.0 / kPi, 3) + " deg)");
  } else if (!rounds.converged) {
    fail(r, CylinderFailure::kNotConverged, "least squares did not converge: " + rounds.message);
  }
}

// The axis point nearest the inliers' centroid and a canonical direction (still in centred coordinates).
Cylinder canonical(const Centred& data, const Rounds& rounds, const CylinderFitOptions& o) {
  Cylinder c = rounds.model;
  Eigen::Vector3d& a = c.axis_direction;
  if (o.axis_prior.norm() > 0.0) {
    if (a.dot(o.axis_prior) < 0.0) a = -a;
  } else {
    Eigen::Index largest = 0;
    a.cwiseAbs().maxCoeff(&largest);
    if (a(largest) < 0.0) a = -a;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i : rounds.inliers) mean += data.points[static_cast<std::size_t>(i)];
  if (!rounds.inliers.empty()) mean /= static_cast<double>(rounds.inliers.size());
  c.axis_point += (mean - c.axis_point).dot(a) * a;
  return c;
}

void describe(CylinderFitResult& r, const Centred& data, const Rounds& rounds, const Cylinder& centred_model) {
  r.inliers = rounds.inliers;
  r.inlier_fraction = static_cast<double>(r.inliers.size()) / static_cast<double>(data.points.size());
  double sum_squares = 0.0;
  for (int i : r.inliers)
    sum_squares += std::pow(signed_distance(centred_model, data.points[static_cast<std::size_t>(i)]), 2);
  r.rms_mm = r.inliers.empty() ? 0.0 : std::sqrt(sum_squares / static_cast<double>(r.inliers.size()));
  r.noise_sigma_mm = rounds.sigma;
  r.threshold_mm = rounds.threshold;
  r.arc_rad = detail::arc_span(data.points, r.inliers, centred_model);
  r.side = detail::wall_side(data.points, data.normals, r.inliers, centred_model);
  const detail::CylinderCovariance cov = detail::cylinder_covariance(data.points, r.inliers, centred_model);
  r.covariance = cov.covariance;
  r.covariance_frame = cov.frame;
  r.radius_std_mm = cov.radius_std_mm;
  r.axis_angle_std_rad = cov.axis_angle_std_rad;
  r.axis_point_std_mm = cov.axis_point_std_mm;
  r.plane_rms_mm = detail::plane_rms(data.points, r.inliers);
  r.sphere_median_mm = detail::sphere_median(data.points);
  r.cylinder_median_mm = detail::median_abs(distances(data.points, centred_model));
  r.refine_rounds = rounds.rounds;
  r.solver_iterations = rounds.iterations;
  r.converged = rounds.converged;
}

}  // namespace

double signed_distance(const Cylinder& cylinder, const Eigen::Vector3d& p) {
  return (p - cylinder.axis_point).cross(cylinder.axis_direction).norm() - cylinder.radius_mm;
}

CylinderFitResult fit_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                               const CylinderFitOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("fit_cylinder: " + why);
  const Centred data = centre(points, normals);
  const double floor = kRelativeFloor * data.extent_mm;
  const double ransac_threshold =
      options.threshold_mm > 0.0
          ? options.threshold_mm
          : std::max(options.inlier_sigmas * detail::local_noise_sigma(data.points, options.normal_neighbors), floor);

  report(options.progress, "cylinder: ransac", 0.0);
  const detail::RansacOutcome ransac =
      detail::ransac_cylinder(data.points, data.normals, ransac_settings(options, ransac_threshold));
  report(options.progress, "cylinder: ransac", 1.0);
  CylinderFitResult result;
  result.ransac_iterations = ransac.iterations;
  result.threshold_mm = ransac_threshold;
  if (!ransac.found || ransac.inliers.size() < 6) {
    const bool flat = ransac.parallel_normal_samples >= ransac.iterations * 9 / 10;
    fail(result, flat ? CylinderFailure::kPlane : CylinderFailure::kNoConsensus,
         flat ? "not a cylinder: the normals are (nearly) all parallel, as on a plane"
              : "not a cylinder: no hypothesis fits (" + std::to_string(ransac.inliers.size()) +
                    " inliers at most; check the radius bounds, the axis prior and the threshold)");
    return result;
  }

  report(options.progress, "cylinder: refine", 0.0);
  Rounds rounds = refine_in_rounds(data, ransac.model, ransac.inliers, ransac_threshold, 0.0, options);
  const detail::ShapeProfile shape = widen_cut_off_shape(data, rounds, options, result);
  Cylinder centred_model = canonical(data, rounds, options);
  describe(result, data, rounds, centred_model);
  result.shape_deviation_mm = shape.max_abs_mm;
  detail::judge_shape_ambiguity(data.points, shape, centred_model, options.max_shape_ambiguity_mm, result);
  result.cylinder = centred_model;
  result.cylinder.axis_point += data.centroid;
  judge(result, rounds, options, floor);
  report(options.progress, "cylinder: refine", 1.0);
  return result;
}

CylinderFitResult fit_cylinder(const Cloud& cloud, const CylinderFitOptions& options) {
  check_consistent(cloud, "fit_cylinder");
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const auto& p : cloud.points) points.emplace_back(p.x, p.y, p.z);
  check_points(points);
  std::vector<Eigen::Vector3d> normals;
  normals.reserve(cloud.size());
  if (cloud.has_normals()) {
    for (const auto& n : cloud.normals) normals.emplace_back(n.normal_x, n.normal_y, n.normal_z);
  } else {
    report(options.progress, "cylinder: normals", 0.0);
    NormalOptions normal_options;
    normal_options.k = std::max(3, options.normal_neighbors);
    for (const auto& n : estimate_normals(cloud, normal_options))
      normals.emplace_back(n.normal_x, n.normal_y, n.normal_z);
    report(options.progress, "cylinder: normals", 1.0);
  }
  CylinderFitResult result = fit_cylinder(points, normals, options);
  if (!cloud.has_normals()) result.side = CylinderSide::kUnknown;  // PCA normals face the viewpoint, not the wall
  return result;
}

}  // namespace conform
