#include "conform/registration/coarse.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "conform/core/error.h"
#include "conform/registration/downsample.h"
#include "conform/registration/surface_noise.h"
#include "cylinder_starts.h"

namespace conform {

namespace {

// The turns of the cylinder starts, in inlier distances at the scan's wall.
constexpr double kCylinderTurnStep = 5.0;

}  // namespace

const char* to_string(CoarseMethod method) {
  switch (method) {
    case CoarseMethod::kNone:
      return "none";
    case CoarseMethod::kPca:
      return "pca";
    case CoarseMethod::kFpfh:
      return "fpfh";
  }
  return "unknown";
}

bool CoarseOptions::IsValid(std::string* error) const {
  std::string why;
  if (!(pca_ambiguity >= 0.0 && pca_ambiguity < 1.0)) {
    why = "pca_ambiguity must be in [0, 1)";
  } else if (!(inlier_noise_factor >= 0.0) || !std::isfinite(inlier_noise_factor) || !(inlier_floor_share >= 0.0) ||
             !std::isfinite(inlier_floor_share)) {
    why = "inlier_noise_factor and inlier_floor_share must be finite and >= 0";
  } else if (refine_iterations < 0 || refine_points < 10) {
    why = "refine_iterations must be >= 0 and refine_points >= 10";
  } else if (method == CoarseMethod::kFpfh && !fpfh.IsValid(&why)) {
    why = "fpfh: " + why;
  } else if ((method != CoarseMethod::kNone || probe_given_start) && !multi_start.IsValid(&why)) {
    why = "multi_start: " + why;
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

CoarseResult coarse_align(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                          const CoarseOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("coarse alignment options: " + why);
  CoarseResult result;
  std::vector<CoarseStart> starts;
  if (options.method == CoarseMethod::kNone) {
    result.winner = "identity";
    if (!options.probe_given_start) return result;
    starts.push_back({"identity", Eigen::Isometry3d::Identity()});
  }
  if (options.method == CoarseMethod::kFpfh) {
    report(options.progress, "coarse: fpfh", 0.0);
    result.fpfh_used = true;
    result.fpfh = fpfh_ransac(scan, reference.points(), options.fpfh);
    report(options.progress, "coarse: fpfh", 1.0);
    int rank = 0;
    for (const FpfhHypothesis& h : result.fpfh.hypotheses) {
      if (h.found) starts.push_back({"fpfh hypothesis " + std::to_string(++rank), h.T_ref_scan});
    }
  }
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : scan) box.extend(p);
  MultiStartOptions multi_start = options.multi_start;
  if (multi_start.inlier_distance_mm == 0.0 && options.inlier_noise_factor > 0.0) {
    SurfaceNoiseOptions noise;
    noise.samples = 2000;
    result.scan_noise_mm = estimate_surface_noise(scan, noise);
    multi_start.inlier_distance_mm = std::max(options.inlier_noise_factor * result.scan_noise_mm,
                                              options.inlier_floor_share * box.diagonal().norm());
  }
  result.inlier_distance_mm = multi_start.inlier_distance_mm;
  // With FPFH the principal-axes starts join only when no hypothesis was found: the best start's probes turned by the
  // reference's own symmetries (multi_start.h) are the mirror poses a near-symmetric part offers, and on a partial
  // scan the scan's axes are not the reference's.
  // Nor does FPFH find one on a tube, whose features are all alike: the fitted cylinders' axes give the starts
  // (cylinder_starts.h) beside the principal axes', turned about the axis in steps of kCylinderTurnStep inlier
  // distances at the scan's farthest point from it (a quick probe reaches a weld bead or a cut end from there).
  if (starts.empty()) {
    if (result.fpfh_used) {
      const double turn_step_mm = multi_start.inlier_distance_mm > 0.0
                                      ? kCylinderTurnStep * multi_start.inlier_distance_mm
                                      : 0.01 * box.diagonal().norm();
      for (CoarseStart& s : detail::cylinder_starts(scan, reference.points(), reference.normals(), turn_step_mm)) {
        starts.push_back(std::move(s));
      }
    }
    for (CoarseStart& s : pca_starts(scan, reference.points(), options.pca_ambiguity)) starts.push_back(std::move(s));
  }
  if (options.probe_thin_walls && result.fpfh_used && multi_start.wall_max_thickness_mm == 0.0) {
    multi_start.wall_max_thickness_mm = options.fpfh.feature_radius * result.fpfh.voxel_mm;
  }
  report(options.progress, "coarse: starts", 0.0);
  result.ranking = rank_starts(scan, reference, starts, multi_start);
  report(options.progress, "coarse: starts", 1.0);
  const StartReport& best = result.ranking.starts[static_cast<std::size_t>(result.ranking.best)];
  result.T_ref_scan = best.T_probe;
  result.winner = best.label;
  if (options.refine_iterations > 0) {
    // The probe stopped after a few steps on a subset: finish the winner on more of the scan, holding only what the
    // data cannot fix at all, so that a motion the fine fit holds (weakly fixed, e.g. along walls a height field
    // barely samples) is held at the data's estimate, not at the probe's.
    report(options.progress, "coarse: refine", 0.0);
    IcpOptions refine = multi_start.probe;
    refine.max_iterations = options.refine_iterations;
    refine.free_tolerance_mm = 1e6;
    refine.free_tolerance_rad = 1e6;
    refine.progress = nullptr;
    const IcpResult r = icp(stride_downsample(scan, options.refine_points), reference, best.T_probe, refine);
    if (r.inlier_fraction >= best.inlier_fraction) result.T_ref_scan = r.T_ref_scan;
    report(options.progress, "coarse: refine", 1.0);
  }
  return result;
}

}  // namespace conform
