#pragma once
// Coarse alignment, so that a user need not pre-place the scan: the starts of one method (principal axes with
// their sign ambiguities, FPFH + RANSAC, or just the identity), ranked by a short ICP from each (multi_start.h).
// With FPFH every RANSAC hypothesis is a start, and the principal-axes starts join them only when RANSAC found none
// (a near-symmetric part's mirror poses come from the reference-symmetry probes of multi_start.h): the best start,
// by inlier share, wins.

#include <string>
#include <vector>

#include "conform/registration/coarse_fpfh.h"
#include "conform/registration/coarse_pca.h"
#include "conform/registration/multi_start.h"

namespace conform {

enum class CoarseMethod {
  kNone,  // start from the given transform (the identity: the scan is already roughly in place); see probe_given_start
  kPca,   // principal axes, every sign combination tried
  kFpfh,  // FPFH + RANSAC, joined by the principal-axes starts when it finds no hypothesis
};

const char* to_string(CoarseMethod method);

struct CoarseOptions {
  CoarseMethod method = CoarseMethod::kPca;
  double pca_ambiguity = 0.1;  // coarse_pca.h
  FpfhOptions fpfh;
  MultiStartOptions multi_start;  // its probe's max_correspondence_distance_mm must be set (finite)
  // Starts are scored by inlier share (multi_start.h) within max(inlier_noise_factor x the scan's noise
  // (surface_noise.h), inlier_floor_share x the scan's bounding-box diagonal), unless multi_start.inlier_distance_mm
  // is set; inlier_noise_factor 0: by truncated RMS only.
  double inlier_noise_factor = 3.0;
  double inlier_floor_share = 1e-3;
  // The winner's probe pose refined further (at most refine_iterations steps of the probe's ICP on at most
  // refine_points scan points, holding only what the data cannot fix at all); 0: the probe's pose as it is.
  int refine_iterations = 30;
  std::size_t refine_points = 20000;
  // kNone: the given start (the identity) is still ranked against itself turned by the reference's candidate
  // symmetries (multi_start.h): a near-symmetric part placed one index off (a flange one bolt hole round) is found
  // there, or the result is ambiguous. false: kNone returns the identity unranked.
  bool probe_given_start = false;
  // With FPFH: the best poses are also probed shifted through the reference's walls thinner than the FPFH support
  // (its radius at the voxel used: a histogram there holds both faces of a plate, so features cannot tell them
  // apart; multi_start.h wall_max_thickness_mm), unless multi_start sets its own thickness.
  bool probe_thin_walls = true;
  ProgressFn progress;  // stages "coarse: fpfh", "coarse: starts", "coarse: refine"

  bool IsValid(std::string* error) const;
};

struct CoarseResult {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // the winning start after its ICP (and refinement)
  MultiStartResult ranking;                                      // empty for kNone unless probe_given_start
  bool fpfh_used = false;
  FpfhResult fpfh;                  // when fpfh_used
  std::string winner;               // the winning start's label ("identity" for kNone)
  double scan_noise_mm = 0.0;       // the scan's own noise, when scoring by share
  double inlier_distance_mm = 0.0;  // the share's distance as used (0: scored by truncated RMS)
};

// Throws conform::Error for invalid options or too few points (see pca_starts, fpfh_ransac).
CoarseResult coarse_align(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                          const CoarseOptions& options);

}  // namespace conform
