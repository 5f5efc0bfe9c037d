#include "conform/pipelines/align/align.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <future>
#include <limits>
#include <optional>
#include <utility>

#include <omp.h>

#include "align/align_coarse_reference.h"
#include "align/align_consistency.h"
#include "align/align_inputs.h"
#include "align/align_verdict.h"
#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/core/io.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/output_set.h"
#include "conform/core/transform_io.h"
#include "conform/registration/downsample.h"

namespace conform {

// reference_is_cloud: with the overlap left to the data (--overlap 0), a cloud reference (another scan: partial
// overlap is the rule) has it estimated in every step; a mesh (the nominal part, which the scan lies on) keeps every
// pair, as trimming even 1-2 % of a plate's worst-fitting points (its steep walls, which fix its in-plane position)
// moved the fit 0.05-0.1 mm at 0.02 mm of noise (AlignMatrixBossPlateMesh).
IcpOptions align_fine_options(const AlignOptions& options, IcpMethod method, double max_distance_mm,
                              bool reference_is_cloud) {
  IcpOptions icp;
  icp.method = method;
  icp.max_correspondence_distance_mm = max_distance_mm;
  icp.estimate_overlap = options.overlap == 0.0 && reference_is_cloud;
  icp.overlap = options.overlap > 0.0 ? options.overlap : 1.0;
  icp.kernel = options.kernel;
  icp.max_iterations = options.max_iterations;
  icp.min_inlier_fraction = std::min(icp.min_inlier_fraction, icp.overlap);
  icp.free_tolerance_mm = options.free_tolerance_mm;
  icp.free_tolerance_rad = options.free_tolerance_deg * M_PI / 180.0;
  icp.progress = options.progress;
  return icp;
}

namespace {

std::vector<Eigen::Vector3d> thin(std::vector<Eigen::Vector3d> points, const AlignOptions& options) {
  if (options.scan_voxel_mm > 0.0) points = voxel_downsample(points, options.scan_voxel_mm);
  return stride_downsample(points, options.max_scan_points);
}

// The RMS of the smallest `share` of the scan's point-to-plane distances to a cloud reference at `T_ref_scan` (each
// point paired to its nearest reference point): the trimmed fit of Chetverikov et al. 2002 at a given overlap.
double trimmed_rms(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                   const Eigen::Isometry3d& T_ref_scan, double share) {
  std::vector<double> distances(scan.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(scan.size()); ++k) {
    const Eigen::Vector3d p = T_ref_scan * scan[static_cast<std::size_t>(k)];
    const auto i = static_cast<std::size_t>(reference.tree().nearest(p.cast<float>()));
    distances[static_cast<std::size_t>(k)] = std::abs(reference.normals()[i].dot(p - reference.points()[i]));
  }
  const auto kept = std::max<std::size_t>(1, static_cast<std::size_t>(share * static_cast<double>(scan.size())));
  std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(kept - 1), distances.end());
  double sum = 0.0;
  for (std::size_t k = 0; k < kept; ++k) sum += distances[k] * distances[k];
  return std::sqrt(sum / static_cast<double>(kept));
}

// Two fits of the scan compared at the same overlap, the smaller of their estimates (trimmed ICP's criterion,
// Chetverikov et al. 2002): the RMS of that share of each one's closest pairs.
struct AtCommonOverlap {
  double share = 0.0;
  double rms_a_mm = 0.0, rms_b_mm = 0.0;
  bool b_better() const { return rms_b_mm < rms_a_mm; }
};

AtCommonOverlap at_common_overlap(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                                  const IcpResult& a, const IcpResult& b) {
  AtCommonOverlap out;
  out.share = std::min(a.inlier_fraction, b.inlier_fraction);
  out.rms_a_mm = trimmed_rms(scan, reference, a.T_ref_scan, out.share);
  out.rms_b_mm = trimmed_rms(scan, reference, b.T_ref_scan, out.share);
  return out;
}

// Fine ICP from `start`. With the overlap estimated and a start the user gave (which may be rough): trimmed to the
// estimated overlap, ICP keeps a right start that half the scan does not overlap, but from a rough start it can stay
// where it began (a LiDAR pair started 0.5 m off); every pair kept, it finds the basin from a rough start, but pairs
// beyond the overlap pull a right start away. So both: the estimated-overlap fit from the start, and from where the
// fit with every pair converged. They are compared at the same overlap, the smaller of the two estimates: the lower
// RMS of that share of the scan's closest pairs wins. Fractional ICP's objective (Phillips et al. 2007, Eq. (3))
// compares fits at different overlaps and there favoured a wrong fit that covered more: a 45 %-overlap room pair
// started at its truth slid 2 deg to a fit claiming 90 % of the scan (trimmed RMS at 51 %: 19.1 mm against 9.5 mm
// at the fit kept; docs/measurements/real_pairs.md).
IcpResult fine_fit(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                   const Eigen::Isometry3d& start, const IcpOptions& fine, bool rough_start) {
  IcpResult direct = icp(scan, reference, start, fine);
  if (!fine.estimate_overlap || !rough_start) return direct;
  IcpOptions quiet = fine;  // the two further runs report no progress of their own
  quiet.progress = nullptr;
  IcpOptions every_pair = quiet;
  every_pair.estimate_overlap = false;
  every_pair.overlap = 1.0;
  // What is asked of it is the basin, not the minimum's last digits: an even subset of the scan, as in ICP's own
  // coarse steps (IcpOptions::coarse_points).
  const IcpResult pulled =
      icp(fine.coarse_points > 0 ? stride_downsample(scan, fine.coarse_points) : scan, reference, start, every_pair);
  // Landed within the direct fit's residual noise of it: one basin, and the fit from there would return to it.
  if (direct.converged &&
      largest_displacement(scan, direct.T_ref_scan, pulled.T_ref_scan) <= direct.degeneracy.noise_mm) {
    return direct;
  }
  IcpResult via = icp(scan, reference, pulled.T_ref_scan, quiet);
  if (!via.converged) return direct;
  if (!direct.converged) return via;
  return at_common_overlap(scan, reference, direct, via).b_better() ? via : direct;
}

// Of a start the user gave (ranking.starts[0]) and its symmetric turns, the one fine ICP starts from: the user's own
// unless a turned one fits better beyond doubt. When the best ties with others (a symmetric part: the data cannot
// tell them apart), the user's own if it is one of them, else the tied one nearest to it: where the user placed the
// scan decides (the verdict says so). -1: nothing ranked.
int given_start_choice(const MultiStartResult& ranking) {
  if (ranking.best < 0 || ranking.starts.empty()) return ranking.best;
  const StartReport& given = ranking.starts.front();
  if (ranking.best == 0 || given.ties_best) return 0;
  if (!ranking.ambiguous) return ranking.best;
  const auto turn_from_given = [&](std::size_t j) {
    return rotation_angle(ranking.starts[j].T_probe * given.T_start.inverse());
  };
  int nearest = ranking.best;
  double nearest_rad = turn_from_given(static_cast<std::size_t>(ranking.best));
  for (std::size_t j = 1; j < ranking.starts.size(); ++j) {
    if (!ranking.starts[j].ties_best) continue;
    const double rad = turn_from_given(j);
    if (rad < nearest_rad) {
      nearest = static_cast<int>(j);
      nearest_rad = rad;
    }
  }
  return nearest;
}

// Where fine ICP starts: the identity, the user's pairs, or the best of the coarse starts.
void place_coarsely(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference, const Mesh& reference_mesh,
                    const AlignOptions& options, double max_distance_mm, AlignResult& result) {
  switch (options.init) {
    case AlignInit::kNone:
      break;
    case AlignInit::kPairs:
      result.pairs = align_point_pairs(detail::read_point_pairs(options.pairs_path, options.scan_mm_per_unit, options.reference_mm_per_unit));
      result.T_start = result.pairs.T_ref_scan;
      result.start = "pairs";
      return;
    case AlignInit::kPca:
    case AlignInit::kFpfh:
      break;
  }
  const bool given = options.init == AlignInit::kNone;
  CoarseOptions coarse;
  coarse.method = given                             ? CoarseMethod::kNone
                  : options.init == AlignInit::kPca ? CoarseMethod::kPca
                                                    : CoarseMethod::kFpfh;
  // A start the user gave is ranked against itself turned by the reference's candidate symmetries: a near-symmetric
  // part placed one index off (a flange one bolt hole round) is found at the right one or called ambiguous. Not
  // refined: unless a turned start wins, fine ICP starts from the user's own.
  coarse.probe_given_start = given;
  if (given) coarse.refine_iterations = 0;
  coarse.fpfh.seed = options.seed;
  // The probes only rank the starts: point-to-plane is as good for that and faster than point-to-surface.
  // The probes find the basin: every pair pulls (a start a few mm off slides home only if the part of the scan that
  // is off the surface is not trimmed away). The estimated overlap is the fine fit's, from the winner's pose.
  coarse.multi_start.probe = align_fine_options(options, IcpMethod::kPointToPlane, max_distance_mm, false);
  coarse.multi_start.probe.max_iterations = 15;
  coarse.multi_start.probe.progress = nullptr;
  coarse.progress = options.progress;
  // Against a mesh, features and scores over its surface at the scan's spacing, not over its vertices
  // (align_coarse_reference.h): a CAD tessellation's vertices are only on its faces' rims.
  const double spacing = reference_mesh.has_faces() ? detail::scan_spacing(scan) : 0.0;
  std::optional<IcpReference> surface;
  if (spacing > 0.0) surface.emplace(detail::coarse_reference(reference_mesh, spacing));
  result.coarse = coarse_align(scan, surface ? *surface : reference, coarse);
  const MultiStartResult& ranking = result.coarse.ranking;
  result.started_from = given ? given_start_choice(ranking) : ranking.best;
  if (!given) {
    result.T_start = result.coarse.T_ref_scan;
    result.start = result.coarse.winner;
  } else if (result.started_from > 0) {  // a turn of the user's start
    const StartReport& from = ranking.starts[static_cast<std::size_t>(result.started_from)];
    result.T_start = from.T_probe;
    result.start = from.label;
    result.warnings.push_back("the start given fits worse than '" + result.start +
                              "' (the reference is near-symmetric): fine ICP started there");
  } else {  // the user's own
    result.T_start = Eigen::Isometry3d::Identity();
    result.start = "identity";
  }
  if (ranking.ambiguous) {
    const StartReport& best = ranking.starts[static_cast<std::size_t>(ranking.best)];
    const StartReport& other = ranking.starts[static_cast<std::size_t>(ranking.runner_up)];
    char shares[160];
    std::snprintf(
        shares, sizeof shares, "inlier share %.3f against %.3f within %.3g mm; truncated RMS %.3g against %.3g mm",
        other.inlier_share, best.inlier_share, result.coarse.inlier_distance_mm, other.score_mm, best.score_mm);
    result.warnings.push_back("the coarse alignment is ambiguous: start '" + other.label +
                              "' fits almost as well as '" + best.label + "' (" + shares +
                              ") at another pose; the part may be symmetric");
  }
}

// The transform and the aligned scan, both or neither.
void write_outputs(const Mesh& scan_mesh, const AlignOptions& options, AlignResult& result) {
  if (options.out_transform_path.empty() && options.out_aligned_path.empty()) return;
  report(options.progress, "write", 0.0);
  OutputSet outputs;
  if (!options.out_transform_path.empty()) write_transform(options.out_transform_path, result.icp.T_ref_scan);
  if (!options.out_aligned_path.empty()) {
    const Mesh aligned = transformed(scan_mesh, result.icp.T_ref_scan);
    if (aligned.has_faces()) {
      write_mesh(options.out_aligned_path, aligned);
    } else {
      write_cloud(options.out_aligned_path, to_cloud(aligned));
    }
  }
  outputs.commit();
  result.transform_path = options.out_transform_path;
  result.aligned_path = options.out_aligned_path;
  report(options.progress, "write", 1.0);
}

// Against another scan the fit's bias is not in its linearised covariance: measured by fitting the reference to
// the scan and by fitting again against a wider-neighbourhood model of the reference's normals
// (align_consistency.h), each added to it. Returns the reverse fit.
detail::FitDiscrepancy add_fit_bias(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                                    const IcpOptions& fine, AlignResult& result) {
  const detail::FitDiscrepancy consistency = detail::inverse_consistency(scan, reference, result.icp, fine);
  const detail::FitDiscrepancy spread = detail::normal_model_spread(scan, reference, result.icp, fine);
  detail::add_bias(consistency, result.icp.degeneracy);
  detail::add_bias(spread, result.icp.degeneracy);
  result.inverse_consistency_mm = consistency.ran ? consistency.largest_displacement_mm : -1.0;
  result.normal_model_mm = spread.ran ? spread.largest_displacement_mm : -1.0;
  return consistency;
}

// The reverse fit (align_consistency.h) landed farther from the forward one than the accuracy asked: on a partial
// overlap ICP has more than one minimum along the motions the overlap fixes poorly, and the forward fit may sit in
// the wrong one (a 31 %-overlap bunny pair: 2.0 deg from its truth with residuals 5.8 times the noise, while the
// reverse fit pointed 4.7 mm away, to the right one). Fine ICP again from the reverse fit's pose; the two fits are
// compared at their common overlap (at_common_overlap), and the better one is kept with its
// own bias fits and verdict. Only where the pose would be refused anyway (its std includes that discrepancy), so a
// pose that is accepted costs nothing more.
void restart_at_reverse_fit(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                            const AlignOptions& options, const IcpOptions& fine,
                            const detail::FitDiscrepancy& reverse, AlignResult& result) {
  AlignResult other = result;
  IcpOptions quiet = fine;
  quiet.progress = nullptr;
  other.icp = fine_fit(scan, reference, reverse.T_ref_scan, quiet, false);
  if (!other.icp.converged) return;
  const AtCommonOverlap compared = at_common_overlap(scan, reference, result.icp, other.icp);
  if (!compared.b_better()) return;
  add_fit_bias(scan, reference, fine, other);
  char why[200];
  std::snprintf(why, sizeof why,
                "the reverse fit landed %.3g mm away and fits better there (trimmed RMS of %.0f %% of the scan %.3g mm "
                "against %.3g mm): fine ICP restarted there",
                reverse.largest_displacement_mm, 100.0 * compared.share, compared.rms_b_mm, compared.rms_a_mm);
  other.warnings.push_back(why);
  other.verdict = detail::judge_alignment(scan, reference, options, other);
  result = std::move(other);
}

}  // namespace

const char* to_string(AlignTrust trust) {
  switch (trust) {
    case AlignTrust::kYes:
      return "yes";
    case AlignTrust::kCheck:
      return "check";
    case AlignTrust::kNo:
      return "no";
  }
  return "unknown";
}

const char* to_string(AlignInit init) {
  switch (init) {
    case AlignInit::kNone:
      return "none";
    case AlignInit::kPca:
      return "pca";
    case AlignInit::kFpfh:
      return "fpfh";
    case AlignInit::kPairs:
      return "pairs";
  }
  return "unknown";
}

IcpMethod default_align_method(bool reference_has_faces) {
  return reference_has_faces ? IcpMethod::kPointToSurface : IcpMethod::kPointToPlane;
}

bool AlignOptions::IsValid(std::string* error) const {
  std::string why;
  if (scan_path.empty()) {
    why = "no scan file given";
  } else if (reference_path.empty()) {
    why = "no reference file given";
  } else if (!(scan_mm_per_unit > 0.0) || !std::isfinite(scan_mm_per_unit) || !(reference_mm_per_unit > 0.0) ||
             !std::isfinite(reference_mm_per_unit)) {
    why = "millimetres per unit of the scan and the reference must be finite and > 0";
  } else if (init == AlignInit::kPairs && pairs_path.empty()) {
    why = "init pairs needs a pairs file";
  } else if (!(max_distance_mm >= 0.0) || std::isnan(max_distance_mm)) {
    why = "max distance must be > 0 mm (0: automatic)";
  } else if (!(overlap >= 0.0 && overlap <= 1.0)) {
    why = "overlap " + std::to_string(overlap) + " must be in (0, 1] (0: estimated)";
  } else if (max_iterations < 1) {
    why = "max iterations must be >= 1";
  } else if (!(scan_voxel_mm >= 0.0) || !std::isfinite(scan_voxel_mm)) {
    why = "scan voxel must be finite and >= 0 mm";
  } else if (max_scan_points < 10) {
    why = "max_scan_points must be >= 10";
  } else if (!(max_size_ratio == 0.0 || max_size_ratio > 1.0)) {
    why = "max_size_ratio must be > 1 (0: no check)";
  } else if (!(free_tolerance_mm > 0.0) || !std::isfinite(free_tolerance_mm) || !(free_tolerance_deg > 0.0) ||
             !std::isfinite(free_tolerance_deg)) {
    why = "free tolerances must be finite and > 0";
  } else if (!(max_noise_ratio == 0.0 || max_noise_ratio > 1.0) || !std::isfinite(max_noise_ratio)) {
    why = "max_noise_ratio must be > 1 (0: no check)";
  } else if (!(pose_tolerance_mm >= 0.0) || !std::isfinite(pose_tolerance_mm)) {
    why = "pose tolerance must be finite and >= 0 mm (0: from the data)";
  } else if (!(tolerance_mm >= 0.0) || !std::isfinite(tolerance_mm)) {
    why = "tolerance must be finite and >= 0 mm (0: not stated)";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

AlignResult run_align(const AlignOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("align: " + why);
  AlignResult result;
  result.init = options.init;
  // FPFH's plugin (PCL's features, ~0.1 s of the loader binding symbols) loads beside the reading and the
  // reference's preparation; a failure is reported where FPFH runs.
  std::future<void> fpfh_loaded;
  if (options.init == AlignInit::kFpfh && omp_get_max_threads() > 1) {
    fpfh_loaded = std::async(std::launch::async, [] {
      try {
        FpfhOptions().IsValid(nullptr);
      } catch (const std::exception&) {
      }
    });
  }

  report(options.progress, "read scan", 0.0);
  const Mesh scan_mesh = detail::read_for_alignment(options.scan_path, "scan", options.scan_mm_per_unit, result.warnings,
                                                    options.cad, &result.cad_inputs);
  report(options.progress, "read scan", 1.0);
  report(options.progress, "read reference", 0.0);
  Mesh reference_mesh = detail::read_for_alignment(options.reference_path, "reference", options.reference_mm_per_unit,
                                                   result.warnings, options.cad, &result.cad_inputs);
  report(options.progress, "read reference", 1.0);
  if (options.max_size_ratio > 0.0) {
    detail::check_sizes(scan_mesh, reference_mesh, options.scan_path, options.reference_path, options.max_size_ratio);
  }
  result.method = options.method.value_or(default_align_method(reference_mesh.has_faces()));
  if (result.method == IcpMethod::kPointToSurface && !reference_mesh.has_faces()) {
    throw Error(options.reference_path + ": point-to-surface needs a reference mesh with faces; this file holds " +
                "points only (use point-to-plane)");
  }
  std::size_t merged = 0;
  const std::vector<Eigen::Vector3d> unique = detail::unique_points(scan_mesh.vertices, &merged);
  if (merged > 0) {
    result.warnings.push_back(options.scan_path + ": " + std::to_string(merged) + " duplicate points merged");
  }
  const std::vector<Eigen::Vector3d> scan = thin(unique, options);
  if (!reference_mesh.has_faces()) {
    std::size_t ref_merged = 0;
    reference_mesh.vertices = detail::unique_points(reference_mesh.vertices, &ref_merged);
    reference_mesh.normals.clear();
  }
  result.scan_points = scan_mesh.vertices.size();
  result.scan_points_used = scan.size();
  result.reference_points = reference_mesh.vertices.size();
  result.reference_faces = reference_mesh.faces.size();

  report(options.progress, "normals", 0.0);
  const IcpReference reference(reference_mesh);
  report(options.progress, "normals", 1.0);
  // Fine point-to-surface ICP needs the triangle index: built beside the coarse stage, which is mostly serial.
  if (result.method == IcpMethod::kPointToSurface && options.init != AlignInit::kNone) reference.prepare_surface();
  result.max_distance_mm = options.max_distance_mm > 0.0
                               ? options.max_distance_mm
                               : kAlignAutoDistanceShare * bounding_box(reference_mesh).diagonal();
  place_coarsely(scan, reference, reference_mesh, options, result.max_distance_mm, result);
  IcpOptions fine = align_fine_options(options, result.method, result.max_distance_mm, !reference_mesh.has_faces());
  // The coarse candidates showed motions along which the pose can move without changing the fit (a cylinder's
  // axis shift and turn): hold every loose motion at the winner's, as free, rather than letting noise move it.
  if (!result.coarse.ranking.free_motions.empty()) fine.start_std_mm = fine.start_std_rad = 0.0;
  result.icp = fine_fit(scan, reference, result.T_start, fine, options.init == AlignInit::kNone);
  detail::FitDiscrepancy consistency;
  if (!reference_mesh.has_faces() && result.icp.converged) {
    report(options.progress, "consistency", 0.0);
    consistency = add_fit_bias(scan, reference, fine, result);
    report(options.progress, "consistency", 1.0);
  }
  result.verdict = detail::judge_alignment(scan, reference, options, result);
  if (consistency.ran && consistency.largest_displacement_mm > result.verdict.pose_tolerance_mm) {
    restart_at_reverse_fit(scan, reference, options, fine, consistency, result);
  }
  if (result.verdict.trust != AlignTrust::kNo) write_outputs(scan_mesh, options, result);
  if (options.keep_geometry) {
    result.scan = scan_mesh;
    result.reference = reference_mesh;
  }
  return result;
}

}  // namespace conform
