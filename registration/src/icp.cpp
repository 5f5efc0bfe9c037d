#include "conform/registration/icp.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/registration/downsample.h"
#include "convergence.h"
#include "gicp.h"
#include "icp_step.h"
#include "pairs.h"
#include "plane_matrix.h"
#include "step_sums.h"

namespace conform {

namespace {

using detail::Pair;

// The subset stage of multi-resolution ICP stops at 100 times the tolerances: its optimum differs from the full
// set's by about that, and the full set takes the last steps.
constexpr double kCoarseToleranceScale = 100.0;
// ... and at this many times the convergence fraction of its own predicted std (convergence.h): the subset's
// optimum is about one of its std from the full set's.
constexpr double kCoarseStdScale = 4.0;
// While ICP creeps (its last two steps point the same way, the last the shorter: convergence.h), residuals of the
// step's size are the pose's error still to be taken out, not outliers: the robust kernel's scale is then at least
// this many times how far the last step moved the scan (its rotation x L plus its translation). Down-weighting them
// slowed a weakly constrained direction to a creep (the fine pair of issue 13: 19 subset steps, each ~0.7 of the
// last; 10 with this floor). Gross outliers, beyond a step, are still down-weighted; once the steps fall below the
// noise the kernel is the residuals' own (the same fixed point). Not while the steps cycle: widening there fed
// larger steps back (a noise-free plate wandered off its pose).
constexpr double kCreepKernelScale = 2.0;
// ... and while it creeps, the step is taken 1 / (1 - rho) times over (rho: how much the last step shrank, the
// geometric series' sum: where the creep would end), at most this many times: the creep's remaining motion in one
// step (fine pair: 25 -> 17 steps, the same pose within 0.001 mm). An overshoot shows as the next step turning
// back, which is not a creep; convergence.h judges the step after a jump with the rate measured before it.
constexpr double kMaxJump = 3.0;
// Plane-to-plane: the scan's normals from this many neighbours, as the reference cloud's (icp_reference.cpp).
constexpr int kScanNormalNeighbours = 16;

// The scan and, for plane-to-plane, its normals: what every pass iterates on.
struct ScanData {
  const std::vector<Eigen::Vector3d>& points;
  std::vector<Eigen::Vector3d> normals;  // empty unless plane-to-plane
};

// What one step saw, at the pose it started from.
struct StepFigures {
  std::vector<std::size_t> inliers;
  std::vector<double> weights;
  double kernel_scale_mm = 0.0;
  PlaneNormalMatrix plane;
  double noise_mm = 0.0;
  double rms_mm = 0.0;
  DegeneracyReport degeneracy;  // what the step holds: with the hold noise
  // Point-to-plane and point-to-surface: the step's normal equations, from the same pass as `plane` (step_sums.h).
  bool has_equations = false;
  Matrix6d H = Matrix6d::Zero();
  Vector6d g = Vector6d::Zero();
};

// One run of ICP's iterations: hold_noise_mm decides what is held (degeneracy.h); `held` is how many directions the
// last recorded step held.
struct Pass {
  double hold_noise_mm = 0.0;
  std::size_t held = 0;
};

// The k-th inlier for step_sums.h.
auto pair_item(const std::vector<Pair>& pairs, const StepFigures& f) {
  return [&pairs, &f](std::size_t k, Eigen::Vector3d& q, Eigen::Vector3d& n, double& r, double& w) {
    const Pair& p = pairs[f.inliers[k]];
    q = p.q;
    n = p.normal;
    r = p.residual;  // n . (q - target)
    w = f.weights.empty() ? 1.0 : f.weights[k];
  };
}

bool along_the_normal(IcpMethod method) {
  return method == IcpMethod::kPointToPlane || method == IcpMethod::kPointToSurface;
}

// origin: a point near the pairs (the sums' origin, step_sums.h); widen_kernel_to_mm: the kernel's scale at least
// this (kCreepKernelScale).
StepFigures evaluate(const std::vector<Pair>& pairs, const IcpOptions& options, double hold_noise_mm,
                     const Eigen::Vector3d& origin, double widen_kernel_to_mm = 0.0) {
  StepFigures f;
  const double overlap = options.estimate_overlap
                             ? detail::fractional_overlap(pairs, options.min_inlier_fraction, options.overlap_lambda)
                             : options.overlap;
  f.inliers = detail::select_inliers(pairs, overlap);
  f.weights = detail::robust_weights(pairs, f.inliers, options.kernel, options.min_kernel_scale_mm, &f.kernel_scale_mm,
                                     widen_kernel_to_mm);
  if (along_the_normal(options.method)) {
    const detail::StepSums sums = detail::step_sums(f.inliers.size(), origin, pair_item(pairs, f));
    f.plane = sums.plane;
    f.rms_mm = sums.rms_mm;
    f.H = sums.H;
    f.g = sums.g;
    f.has_equations = true;
  } else {
    f.plane = detail::plane_normal_matrix_of(
        f.inliers.size(), [&](std::size_t k) -> const Eigen::Vector3d& { return pairs[f.inliers[k]].q; },
        [&](std::size_t k) -> const Eigen::Vector3d& { return pairs[f.inliers[k]].normal; },
        [&](std::size_t k) {
          const Pair& p = pairs[f.inliers[k]];
          return p.normal.dot(p.q - p.target);
        });
    f.rms_mm = detail::inlier_rms(pairs, f.inliers);
  }
  // The constraint is the point-to-plane one (degeneracy.h) for every method, and so is the noise that scales it.
  const bool along_normal = options.method == IcpMethod::kPointToPoint;
  f.noise_mm = f.kernel_scale_mm > 0.0 && !along_normal
                   ? f.kernel_scale_mm
                   : detail::noise_scale(pairs, f.inliers, options.min_kernel_scale_mm, along_normal);
  f.degeneracy = analyze_constraint(f.plane, hold_noise_mm, options.free_tolerance_mm, options.free_tolerance_rad,
                                    options.free_dof, options.free_relative_eigenvalue, options.start_std_mm,
                                    options.start_std_rad);
  return f;
}

// The report is the constraint at the residuals' own noise, whatever the step held.
// Called when a pass of iterations ends: only the last step's figures are reported.
void record(const std::vector<Pair>& pairs, const StepFigures& f, std::size_t scan_size, const IcpOptions& options,
            Pass& pass, IcpResult& result) {
  result.rms_mm = f.rms_mm;
  result.inliers = f.inliers.size();
  result.inlier_fraction = static_cast<double>(f.inliers.size()) / static_cast<double>(scan_size);
  result.kernel_scale_mm = f.kernel_scale_mm;
  PlaneNormalMatrix plane = f.plane;
  if (f.has_equations) {
    detail::residual_moments_of(f.inliers.size(), options.kernel == RobustKernel::kHuber, plane, pair_item(pairs, f));
  }
  result.degeneracy = analyze_constraint(plane, f.noise_mm, options.free_tolerance_mm, options.free_tolerance_rad,
                                         options.free_dof, options.free_relative_eigenvalue, options.start_std_mm,
                                         options.start_std_rad);
  pass.held = f.degeneracy.degenerate_basis.size();
}

// Once, at the end of a pass (not in the loop): the record of the last pairs, its covariance bounded by the
// cluster-robust sandwich over spatial blocks (degeneracy.h). The scan is in Z-curve order (pairs.h), so contiguous
// runs of the inliers are compact patches.
void record_final(const std::vector<Pair>& pairs, std::size_t scan_size, const IcpOptions& options, Pass& pass,
                  IcpResult& result) {
  if (options.covariance_clusters < 2 || pairs.empty()) return;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the step sums' origin: any point near the pairs
  for (const Pair& p : pairs) origin += p.q;
  StepFigures f = evaluate(pairs, options, pass.hold_noise_mm, origin / static_cast<double>(pairs.size()));
  if (f.inliers.size() < options.min_correspondences || !(f.plane.length_scale_mm > 0.0)) return;
  detail::add_cluster_moment(
      f.inliers.size(), [&](std::size_t k) -> const Eigen::Vector3d& { return pairs[f.inliers[k]].q; },
      [&](std::size_t k) -> const Eigen::Vector3d& { return pairs[f.inliers[k]].normal; },
      [&](std::size_t k) {
        const Pair& p = pairs[f.inliers[k]];
        return f.weights[k] * p.normal.dot(p.q - p.target);
      },
      options.covariance_clusters, f.plane);
  record(pairs, f, scan_size, options, pass, result);
}

void check_input(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                 const Eigen::Isometry3d& T_ref_scan_init, const IcpOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("ICP options: " + why);
  if (scan.empty()) throw Error("ICP: the scan has no points");
  for (std::size_t i = 0; i < scan.size(); ++i) {
    if (!scan[i].allFinite()) throw Error("ICP: scan point " + std::to_string(i) + " is not finite; clean it first");
  }
  if (!T_ref_scan_init.matrix().allFinite()) throw Error("ICP: the initial transform is not finite");
  if (options.method == IcpMethod::kPointToSurface) reference.surface();  // throws, naming the problem
}

// Steps from result.T_ref_scan on `points` until a step moves less than the tolerances times tolerance_scale
// (converged) or result.iterations reaches max_iterations; stops with kTooFewCorrespondences when too few pairs are
// left. `result` keeps the figures of the last pairs found (at the pose the last step started from).
void iterate(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
             const IcpReference& reference, const IcpOptions& options, const detail::PairRules& rules,
             double tolerance_scale, int max_iterations, std::vector<Pair>& pairs, Pass& pass, IcpResult& result) {
  const bool point_to_point = options.method == IcpMethod::kPointToPoint;
  detail::ConvergenceTest convergence(
      options.convergence_std_fraction * (tolerance_scale > 1.0 ? kCoarseStdScale : 1.0),
      tolerance_scale * options.rotation_tolerance_rad, tolerance_scale * options.translation_tolerance_mm);
  detail::PairCache cache;  // the last step's searches, reused where exact: late steps search almost nothing
  cache.reset(points.size(), options.method == IcpMethod::kPointToSurface);
  const Eigen::Vector3d scan_centre = centroid(points);  // the step sums' origin, moved with the scan
  double last_motion_mm = 0.0;  // how far the last step moved the scan (at most), mm: the kernel's floor
  while (result.iterations < max_iterations) {
    report(options.progress, "icp", static_cast<double>(result.iterations) / options.max_iterations);
    detail::find_pairs(points, normals, result.T_ref_scan, reference, rules, pairs, &cache);
    const StepFigures f = evaluate(pairs, options, pass.hold_noise_mm, result.T_ref_scan * scan_centre,
                                   kCreepKernelScale * last_motion_mm);
    if (f.inliers.size() < options.min_correspondences || !(f.plane.length_scale_mm > 0.0)) {
      result.termination = IcpTermination::kTooFewCorrespondences;
      record(pairs, f, points.size(), options, pass, result);
      return;
    }
    const bool frozen = options.freeze_degenerate && f.degeneracy.degenerate();
    Eigen::Isometry3d delta;
    if (point_to_point && options.free_dof.all() && !frozen) {
      delta = detail::horn_step(pairs, f.inliers, f.weights);
    } else if (f.has_equations) {
      const Eigen::MatrixXd basis = detail::allowed_basis(options.free_dof, f.degeneracy, options.freeze_degenerate);
      delta = detail::solve_step(f.H, f.g, f.plane.centre, f.plane.length_scale_mm, basis);
    } else {
      const Eigen::MatrixXd basis = detail::allowed_basis(options.free_dof, f.degeneracy, options.freeze_degenerate);
      delta = detail::gauss_newton_step(pairs, f.inliers, f.weights, options.method, f.plane.centre,
                                        f.plane.length_scale_mm, basis, options.gicp_epsilon);
    }
    const Eigen::Vector3d centre = f.plane.centre;
    ++result.iterations;
    result.last_rotation_rad = rotation_angle(delta);
    result.last_translation_mm = (delta * centre - centre).norm();
    const bool converged = convergence.converged(delta, f.plane, f.noise_mm);  // convergence.h, Eq. (2)
    last_motion_mm = convergence.creeping()
                         ? result.last_translation_mm + result.last_rotation_rad * f.plane.length_scale_mm
                         : 0.0;
    result.last_step_std = convergence.last_std_fraction();
    const double jump = converged ? 1.0 : convergence.jump_factor(kMaxJump);
    if (jump > 1.0) {
      delta = detail::scaled_motion(delta, centre, jump);
      convergence.jumped();
    }
    result.T_ref_scan = delta * result.T_ref_scan;
    if (converged) {
      record(pairs, f, points.size(), options, pass, result);  // the figures at the pose this step started from
      result.converged = true;
      result.termination = IcpTermination::kConverged;
      return;
    }
  }
}

// ICP from T_ref_scan_init with `pass.hold_noise_mm` deciding what is held.
IcpResult run_pass(const ScanData& scan, const IcpReference& reference, const Eigen::Isometry3d& T_ref_scan_init,
                   const IcpOptions& options, Pass& pass) {
  detail::PairRules rules;
  rules.method = options.method;
  rules.max_distance_mm = options.max_correspondence_distance_mm;
  IcpResult result;
  result.T_ref_scan = T_ref_scan_init;
  std::vector<Pair> pairs;
  if (options.coarse_points > 0 && scan.points.size() > 2 * options.coarse_points) {
    // Multi-resolution: the big steps on an even subset, the last ones (and the tolerances) on every point.
    // At most half the iterations, so that the full set always has its share. (The same stride picks the normals.)
    iterate(stride_downsample(scan.points, options.coarse_points),
            scan.normals.empty() ? scan.normals : stride_downsample(scan.normals, options.coarse_points), reference,
            options, rules, kCoarseToleranceScale, std::max(1, options.max_iterations / 2), pairs, pass, result);
    result.converged = false;
    result.termination = IcpTermination::kFailure;  // the full set decides, whatever the subset found
  }
  iterate(scan.points, scan.normals, reference, options, rules, 1.0, options.max_iterations, pairs, pass, result);
  if (result.termination == IcpTermination::kFailure) {
    // Out of iterations: the figures at the final pose, which may be far from where the last step started. (When
    // converged, the last step moved less than the tolerances and its pairs' figures stand for the final pose.)
    result.termination = IcpTermination::kMaxIterations;
    detail::find_pairs(scan.points, scan.normals, result.T_ref_scan, reference, rules, pairs);
    const StepFigures f = evaluate(pairs, options, pass.hold_noise_mm, result.T_ref_scan * centroid(scan.points));
    record(pairs, f, scan.points.size(), options, pass, result);
  }
  record_final(pairs, scan.points.size(), options, pass, result);
  if (result.converged && result.inlier_fraction < options.min_inlier_fraction) {
    result.converged = false;
    result.termination = IcpTermination::kInsufficientOverlap;
  }
  return result;
}

}  // namespace

double rotation_angle(const Eigen::Isometry3d& T) {
  // atan2 of |sin| and cos from the rotation's skew part and trace: accurate near 0 and near pi alike.
  const Eigen::Matrix3d R = T.linear();
  const Eigen::Vector3d s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * s.norm(), 0.5 * (R.trace() - 1.0));
}

IcpResult icp(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
              const Eigen::Isometry3d& T_ref_scan_init, const IcpOptions& options) {
  check_input(scan, reference, T_ref_scan_init, options);
  // Away from the optimum the residuals are the pose's error, not noise: holding by them would hold everything at
  // a wrong start. So the first pass holds only what the noise floor cannot fix (a plane's in-plane motions); when
  // the residuals' noise at its end leaves more directions too loose, a second pass from the start holds them.
  const std::vector<Eigen::Vector3d> ordered = detail::spatially_ordered(scan);  // for the caches (pairs.h)
  ScanData data{ordered, {}};
  if (options.method == IcpMethod::kPlaneToPlane) data.normals = detail::plane_normals(ordered, kScanNormalNeighbours);
  Pass first{options.min_kernel_scale_mm, 0};
  IcpResult result = run_pass(data, reference, T_ref_scan_init, options, first);
  if (result.converged && options.freeze_degenerate && result.degeneracy.degenerate_basis.size() > first.held) {
    Pass second{result.degeneracy.noise_mm, 0};
    const int iterations = result.iterations;
    result = run_pass(data, reference, T_ref_scan_init, options, second);
    result.iterations += iterations;
  }
  report(options.progress, "icp", 1.0);
  return result;
}

}  // namespace conform
