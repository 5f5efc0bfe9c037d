#pragma once
// Coarse alignment, so that a user need not pre-place the scan: the starts of one method (principal axes with
// their sign ambiguities, FPFH + RANSAC, or just the identity), ranked by a short ICP from each (multi_start.h).
// FPFH's answer is trusted alone when RANSAC found a hypothesis backed by enough of the scan; otherwise (repetitive or
// featureless shape, or little overlap) the principal-axes starts join it and the best one wins.

#include <string>
#include <vector>

#include "conform/registration/coarse_fpfh.h"
#include "conform/registration/coarse_pca.h"
#include "conform/registration/multi_start.h"

namespace conform {

enum class CoarseMethod {
  kNone,  // start from the given transform (the identity: the scan is already roughly in place)
  kPca,   // principal axes, every sign combination tried
  kFpfh,  // FPFH + RANSAC, joined by the principal-axes starts when its answer is weak
};

const char* to_string(CoarseMethod method);

struct CoarseOptions {
  CoarseMethod method = CoarseMethod::kPca;
  double pca_ambiguity = 0.1;  // coarse_pca.h
  FpfhOptions fpfh;
  // Below this RANSAC inlier fraction the FPFH answer is not trusted alone.
  double fpfh_trusted_fraction = 0.5;
  MultiStartOptions multi_start;  // its probe's max_correspondence_distance_mm must be set (finite)
  ProgressFn progress;            // stages "coarse: fpfh", "coarse: starts"

  bool IsValid(std::string* error) const;
};

struct CoarseResult {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // the winning start after its short ICP
  MultiStartResult ranking;                                      // empty for kNone
  bool fpfh_used = false;
  FpfhResult fpfh;     // when fpfh_used
  std::string winner;  // the winning start's label ("identity" for kNone)
};

// Throws conform::Error for invalid options or too few points (see pca_starts, fpfh_ransac).
CoarseResult coarse_align(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                          const CoarseOptions& options);

}  // namespace conform
