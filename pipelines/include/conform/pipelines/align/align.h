#pragma once
// `conform align`: where is the scan? Reads the scan and the reference, cleans them (points with NaN or infinite
// coordinates dropped with a warning, duplicate scan points merged), thins the scan, estimates reference normals,
// places the scan coarsely (none, principal axes, FPFH + RANSAC, or user point pairs; several starts ranked when the
// method leaves a choice), refines with ICP (registration/icp.h) and reports the fit: T_ref_scan, convergence, RMS,
// inlier fraction, the pose's predicted standard deviations and the motions the scan does not constrain, and a
// verdict: the residuals against the scan's own noise, the overlap, the constraint. Writes the transform and the
// aligned scan when asked, only when the verdict is not "no", whole or not at all.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/cad.h"
#include "conform/core/mesh.h"
#include "conform/core/progress.h"
#include "conform/registration/coarse.h"
#include "conform/registration/icp.h"
#include "conform/registration/point_pairs.h"

namespace conform {

enum class AlignInit {
  kNone,   // the scan is roughly in place already
  kPca,    // principal axes, all sign combinations tried (scan and reference cover the same surface)
  kFpfh,   // FPFH features + RANSAC (partial overlap), with the principal-axes starts when its answer is weak
  kPairs,  // point pairs from pairs_path (Horn's method)
};

const char* to_string(AlignInit init);

// The automatic maximum pair distance (AlignOptions::max_distance_mm 0), as a share of the reference's bounding-box
// diagonal: wide enough for a scan placed within a few degrees and a few percent, narrow enough that a scan beside
// the part finds nothing.
inline constexpr double kAlignAutoDistanceShare = 0.1;
// The accuracy asked of the pose by default (AlignOptions::pose_tolerance_mm 0, no tolerance stated): this many
// times the larger of the scan's and the fit's noise, taken as at least kAlignFinestNoiseMm, against a cloud and
// against a mesh alike (align_verdict.cpp says how it was calibrated).
inline constexpr double kAlignPoseNoiseShare = 2.7;
inline constexpr double kAlignFinestNoiseMm = 0.02;

// The fine method when AlignOptions::method is empty: point-to-surface against a mesh, point-to-plane against a cloud
// (docs/align.md, **Fine methods**: what each measured).
IcpMethod default_align_method(bool reference_has_faces);

struct AlignOptions {
  std::string scan_path;       // cloud or mesh, any format read_geometry reads
  std::string reference_path;  // mesh (point-to-surface possible) or cloud; or CAD (.step .stp .iges .igs)
  // Millimetres per unit of the scan file and of the pairs file's scan columns (1000 for metres), and of the
  // reference and the pairs file's reference columns; a CAD file keeps the units written in it.
  double scan_mm_per_unit = 1.0;
  double reference_mm_per_unit = 1.0;
  CadReadOptions cad;          // a CAD reference: its tessellation (core/cad.h)

  std::optional<IcpMethod> method;  // empty: default_align_method(the reference has faces)
  AlignInit init = AlignInit::kNone;
  // kPairs: one pair per line, `scan_x scan_y scan_z reference_x reference_y reference_z` (file units; spaces or
  // commas; '#' starts a comment), at least 3 pairs not on one line.
  std::string pairs_path;

  double max_distance_mm = 0.0;  // ICP's maximum pair distance; 0: kAlignAutoDistanceShare of the reference's box diagonal
  // Trimmed ICP: the share of the scan expected to overlap the reference, (0, 1]; 0: estimated from the pairs'
  // distances in every step against a cloud (fractional ICP, registration/icp_options.h estimate_overlap), every
  // pair kept against a mesh.
  double overlap = 0.0;
  int max_iterations = 50;
  RobustKernel kernel = RobustKernel::kHuber;
  double scan_voxel_mm = 0.0;            // > 0: the scan thinned to one point per voxel before ICP
  std::size_t max_scan_points = 200000;  // more scan points than this are thinned by an even stride
  // The scan's bounding-box diagonal more than this many times larger or smaller than the reference's is taken for a
  // unit mix-up (an error suggesting --units); 0: no check.
  double max_size_ratio = 20.0;
  std::uint64_t seed = 1;  // FPFH's RANSAC
  // A weak motion is held at the start when its predicted standard deviation (from the residuals' noise and the
  // constraint the surface gives, registration/degeneracy.h) exceeds this along (mm) or about (deg) an axis and the
  // start is known better (the coarse stage found the fit unchanged along it: a tube's axis).
  double free_tolerance_mm = 0.02;
  double free_tolerance_deg = 0.01;
  // The accuracy asked of the pose: the largest predicted displacement std of any scan point
  // (registration/degeneracy.h, largest_displacement_std_mm; against a cloud with the fit's bias, AlignVerdict), mm.
  // 0: from the data and the job: tolerance_mm / 6 when the inspection tolerance is stated (three std use at most
  // half of it), else 2.7 times (against a mesh sqrt(3) times) the larger of the scan's own noise and the fit's
  // residual noise, taken as at least 0.02 mm (align_verdict.cpp). A pose from --init pca/fpfh that misses it is
  // refused, one from a start the user gave is "check".
  double pose_tolerance_mm = 0.0;
  // The inspection tolerance +-t the pose serves (what compare --tolerance will check), mm; 0: not stated.
  double tolerance_mm = 0.0;
  // The fit's residual noise more than this many times the scan's own (plus the reference cloud's) noise: the pose
  // is not consistent with the data (a wrong pose, or a part far from its reference): not trusted, exit 1. Above 2
  // the verdict is "check". 0: no check. Loose because the local noise estimate misses sampling effects: a LiDAR
  // pair (small_gicp) at its right pose has residuals 13 times its ring-wise local noise.
  double max_noise_ratio = 20.0;

  std::string out_transform_path;  // T_ref_scan, 4x4 text (mm); empty: not written
  std::string out_aligned_path;    // the scan in the reference frame (mm), mesh or cloud as read; empty: not written

  ProgressFn progress;  // stages "read scan", "read reference", "normals", "coarse: ...", "icp", "consistency", "write"
  bool keep_geometry = false;  // keep the scan and the reference (mm, as read) in the result, for a report

  bool IsValid(std::string* error) const;
};

// Whether to trust the pose, and the figures that say so.
enum class AlignTrust {
  kYes,    // converged, residuals near the noise, enough of the scan, every motion fixed
  kCheck,  // usable with care: some motions held at the start, residuals a few times the noise, or little overlap
  kNo,     // not converged, residuals far above the noise, or another start fits as well: no pose is returned
};

const char* to_string(AlignTrust trust);  // "yes", "check", "no"

struct AlignVerdict {
  AlignTrust trust = AlignTrust::kNo;
  double scan_noise_mm = 0.0;        // the scan's own noise (registration/surface_noise.h)
  double reference_noise_mm = 0.0;   // the reference cloud's (0 for a mesh)
  double expected_noise_mm = 0.0;    // sqrt(scan^2 + reference^2): what the residuals should be at the right pose
  double fit_noise_mm = 0.0;         // the residuals' robust std at the result (icp.degeneracy.noise_mm)
  double noise_ratio = 0.0;          // fit / expected
  double overlap = 0.0;              // the share of the scan within the maximum distance and kept (inlier fraction)
  // The largest predicted displacement std of a scan point (estimated motions), with the inverse-consistency and
  // normal-model biases (AlignResult::inverse_consistency_mm, normal_model_mm) added in quadrature against a cloud
  // reference.
  double pose_std_mm = 0.0;
  double pose_tolerance_mm = 0.0;    // what was asked of it (AlignOptions::pose_tolerance_mm, resolved)
  std::vector<std::string> reasons;  // why not kYes, one sentence each
  std::string summary;               // one line: whether to trust the pose and why
};

struct AlignResult {
  IcpResult icp;                                // the fine fit; icp.converged says whether it succeeded
  IcpMethod method = IcpMethod::kPointToPlane;  // as used
  AlignInit init = AlignInit::kNone;
  std::string start;       // the start that won: "identity", "pairs", "fpfh", "pca +x+y", ...
  CoarseResult coarse;     // kPca, kFpfh: every start and its score; kNone: the start given and its symmetric turns
  // The coarse start fine ICP ran from (index into coarse.ranking.starts): the best, or from a start the user gave
  // the user's own (0) or the tied turn nearest to it; -1 when none was ranked.
  int started_from = -1;
  PointPairsResult pairs;  // kPairs: the transform and each pair's residual
  Eigen::Isometry3d T_start = Eigen::Isometry3d::Identity();  // where fine ICP started
  double max_distance_mm = 0.0;                               // as used
  // Against a cloud reference: the largest displacement of a scan point between the fit and the same fit with the
  // roles swapped (the inverse-consistency check, a measure of the fit's bias; added to icp.degeneracy's
  // covariance), mm; 0 against a mesh, -1 when the swapped fit did not converge.
  double inverse_consistency_mm = 0.0;
  // Against a cloud reference: the largest displacement of a scan point between the fit and the same fit against
  // the reference's normals taken over a wider neighbourhood (the normal-model spread, a measure of the model's own
  // uncertainty; added to icp.degeneracy's covariance), mm; 0 against a mesh, -1 when that fit did not converge.
  double normal_model_mm = 0.0;
  std::size_t scan_points = 0;                                // read (finite)
  std::size_t scan_points_used = 0;                           // after merging duplicates and thinning
  std::size_t reference_points = 0;
  std::size_t reference_faces = 0;
  AlignVerdict verdict;               // whether to trust icp.T_ref_scan; outputs are written unless kNo
  std::vector<std::string> warnings;  // dropped points, merged duplicates, ambiguous starts
  std::vector<CadReport> cad_inputs;  // each CAD file read: units, bodies, deflection, triangles
  std::string transform_path;         // written; empty when not
  std::string aligned_path;
  Mesh scan;       // with options.keep_geometry: the scan as read, in its own frame, mm (else empty)
  Mesh reference;  // with options.keep_geometry: the reference as read, mm (else empty)
};

// The fine ICP's options align uses for `options` (its method, maximum pair distance and the reference's kind
// decided): trimmed to options.overlap, or with the overlap estimated in every step against a cloud when it is 0 (a
// mesh keeps every pair), align's kernel, iterations and free-motion tolerances, its progress. For a job that runs
// align's fine fit on geometry it already holds (inspect's best fit after --transform).
IcpOptions align_fine_options(const AlignOptions& options, IcpMethod method, double max_distance_mm,
                              bool reference_is_cloud);

// Throws conform::Error for bad input: invalid options, unreadable or empty files, a pairs file that is not 3+
// valid pairs, scan and reference of wildly different sizes (units), point-to-surface against a cloud, an output
// that cannot be written. Not converging, or a pose that is not consistent, is not an error: see result.verdict.
AlignResult run_align(const AlignOptions& options);

}  // namespace conform
