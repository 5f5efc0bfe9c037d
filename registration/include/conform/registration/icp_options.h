#pragma once
// How fine ICP runs: the variant, the robust estimation, when to stop, which degrees of freedom may move.

#include <cstddef>
#include <limits>
#include <string>

#include "conform/core/progress.h"

namespace conform {

enum class IcpMethod {
  // Besl & McKay 1992: each scan point paired with its nearest reference point; the step is Horn's closed form
  // (horn.h). Converges linearly; biased by the reference's point spacing.
  kPointToPoint,
  // Chen & Medioni 1992: the distance along the reference normal at the nearest reference point; a Gauss-Newton step
  // on the linearised rotation. Converges in a few iterations; needs reference normals (estimated when missing).
  kPointToPlane,
  // The closest point on the reference mesh's triangles (not only its vertices), moved onto the smooth surface the
  // vertices and their normals describe (Phong tessellation, except across creases), then the distance along the
  // normal there, solved as point-to-plane. Needs a reference with faces. Free of the flat facets' chord error.
  kPointToSurface,
  // Generalized ICP (Segal, Haehnel & Thrun 2009), "plane-to-plane": the nearest reference point, and the distance
  // weighted by the inverse of the sum of both points' surface covariances (each a plane: small along its normal,
  // from k neighbours of the scan and of the reference). Uses the local shape of both clouds.
  kPlaneToPlane,
};

// Down-weights large residuals r with a scale s estimated from the residuals themselves (1.4826 x their median
// absolute value, the MAD of a zero-mean distribution; Huber 1981, Tukey's biweight after Beaton & Tukey 1974).
enum class RobustKernel {
  kNone,   // least squares
  kHuber,  // w = 1 for |r| <= 1.345 s, else 1.345 s / |r|: 95% efficient under Gaussian noise
  kTukey,  // w = (1 - (r / 4.685 s)^2)^2 for |r| < 4.685 s, else 0: ignores gross outliers entirely
};

enum class IcpTermination {
  kFailure,                // not run, or stopped by an error (the default until proven otherwise)
  kConverged,              // the last step moved a small fraction of the pose's predicted std (or below the tolerances)
  kMaxIterations,          // the iteration limit came first
  kTooFewCorrespondences,  // fewer scan points than needed found a reference point within the maximum distance
  kInsufficientOverlap,    // converged, but fewer than min_inlier_fraction of the scan points are inliers
};

// "converged", "max_iterations", "too_few_correspondences", "insufficient_overlap", "failure" (the JSON words).
const char* to_string(IcpTermination termination);
const char* to_string(IcpMethod method);
const char* to_string(RobustKernel kernel);

// The degrees of freedom ICP may change, as rotations about the reference frame's axes through the scan's centroid
// and translations along them. All free by default; e.g. a turntable: rx = ry = false, tz = false.
struct FreeDof {
  bool rx = true, ry = true, rz = true;
  bool tx = true, ty = true, tz = true;

  bool all() const { return rx && ry && rz && tx && ty && tz; }
  int count() const { return int{rx} + int{ry} + int{rz} + int{tx} + int{ty} + int{tz}; }
  bool free(int i) const { return i == 0 ? rx : i == 1 ? ry : i == 2 ? rz : i == 3 ? tx : i == 4 ? ty : tz; }
};

struct IcpOptions {
  IcpMethod method = IcpMethod::kPointToPlane;

  // --- robust estimation ---
  // Pairs farther apart than this (Euclidean, mm) are ignored. Infinity: no limit.
  double max_correspondence_distance_mm = std::numeric_limits<double>::infinity();
  // Trimmed ICP (Chetverikov et al. 2002; CloudCompare's "final overlap"): only this fraction of the scan points,
  // those with the smallest distances, takes part in each step. In (0, 1]; 1 keeps every pair within the distance.
  double overlap = 1.0;
  // Fractional ICP (Phillips, Liu & Tomasi 2007): each step estimates the overlap from the pairs' distances, the
  // share f >= min_inlier_fraction minimising RMSD(f) / f^overlap_lambda, and trims to it; `overlap` is then unused.
  // For a scan whose overlap with the reference is not known: the pairs beyond it (a room scan's other half) no longer
  // pull a right start away.
  bool estimate_overlap = false;
  double overlap_lambda = 3.0;  // their recommended exponent; larger keeps more pairs
  RobustKernel kernel = RobustKernel::kHuber;
  // The kernel's scale never drops below this (mm), so that a noise-free fit does not weight its last residuals of
  // 1e-12 mm against each other.
  double min_kernel_scale_mm = 1e-3;

  // Generalized ICP: each point's covariance is a disc, 1 in its tangent plane and this along its normal (Segal et al.
  // 2009, Sec. III-B); in (0, 1].
  double gicp_epsilon = 1e-3;

  // --- termination (convergence.h in src/, Eq. (2)) ---
  // Converged when a step is below this fraction of the pose's own predicted standard deviation (its Mahalanobis
  // length under sigma^2 (N H)^-1, with what is still to come if the steps shrink geometrically): the pose then
  // moves by a fraction of what the data resolves. 0.25: pairs flipping at the noise level make ICP cycle among poses
  // up to 0.3 std apart (a 0.25 mm-noise profiler scan against its golden sample); such a cycle adds at most
  // sqrt(1 + 0.25^2) - 1 = 3 % to the reported std.
  double convergence_std_fraction = 0.25;
  // ... or when a step rotates less than this and moves the scan's centroid less than that: the numerical floor of
  // a noise-free fit (whose noise is the kernel's floor), tight enough that it lands within 1e-6 mm.
  double rotation_tolerance_rad = 1e-6;  // 5.7e-5 deg
  double translation_tolerance_mm = 1e-4;
  int max_iterations = 50;  // steps in all, both stages of multi-resolution
  // Multi-resolution: a scan of more than twice this many points first iterates on an even subset of this many, to
  // 100 times the tolerances, then on every point. The subset takes the big steps cheaply; the result is the full
  // set's. 0: every point in every step.
  std::size_t coarse_points = 20000;
  // Fewer pairs than this in a step: stop (kTooFewCorrespondences). At least 3.
  std::size_t min_correspondences = 6;
  // A converged fit with fewer inliers than this fraction of the scan points is reported as not converged
  // (kInsufficientOverlap): it matched a sliver of the scan. In [0, overlap].
  double min_inlier_fraction = 0.05;

  // --- degrees of freedom ---
  FreeDof free_dof;
  // A motion is free (degenerate, degeneracy.h) when its predicted standard deviation, sigma / sqrt(N lambda) from
  // the residuals' noise sigma and the point-to-plane normal matrix, exceeds this along (mm) or about (rad) an
  // axis. Above a few micrometres from 100k points on a weak feature; a tube's axis is orders of magnitude looser.
  double free_tolerance_mm = 0.02;
  double free_tolerance_rad = 1.7453292519943295e-4;  // 0.01 deg
  // How well the start is known, along (mm) and about (rad) every axis: a loose direction (above the tolerances) is
  // held only where the data cannot do better than the start, i.e. its predicted std also exceeds these. Infinity
  // (nothing known about the start: a coarse search's or a user's rough placement): a weak direction the data does
  // measure is estimated, however loosely, and reported with its std; only what the data cannot fix at all (below)
  // is held. 0: every loose direction is held (the start is exact).
  double start_std_mm = std::numeric_limits<double>::infinity();
  double start_std_rad = std::numeric_limits<double>::infinity();
  // Directions whose eigenvalue is below this fraction of the largest are free whatever their predicted std: only
  // second-order effects fix them (a tube's axis against a faceted mesh: ~1e-5), with systematic errors that do not
  // average out. In [0, 1); the ribbed plate's weak but real direction is 2.7e-4.
  double free_relative_eigenvalue = 1e-4;
  // The reported covariance is bounded below by the cluster-robust sandwich over this many spatial blocks of the
  // final pairs (degeneracy.h; Liang & Zeger 1986): it sees residuals correlated within a patch, which the per-pair
  // estimates count as independent. A bias shared by all the pairs that fix a direction is absorbed by the fit and
  // seen by no residual-based estimate (docs/align.md, Constraint). Computed once, after the last step. 0, 1: off.
  std::size_t covariance_clusters = 32;
  // Hold free directions at their start value instead of letting noise move them (Zhang et al. 2016, "On
  // degeneracy of optimization-based state estimation problems"). They are reported either way.
  bool freeze_degenerate = true;

  ProgressFn progress;  // stage "icp", fraction = iteration / max_iterations

  // False (and why, naming the option) for values out of range or not finite.
  bool IsValid(std::string* error) const;
};

}  // namespace conform
