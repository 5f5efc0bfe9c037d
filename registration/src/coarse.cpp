#include "conform/registration/coarse.h"

#include <cmath>
#include <utility>

#include "conform/core/error.h"

namespace conform {

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
  } else if (!(fpfh_trusted_fraction >= 0.0 && fpfh_trusted_fraction <= 1.0)) {
    why = "fpfh_trusted_fraction must be in [0, 1]";
  } else if (method == CoarseMethod::kFpfh && !fpfh.IsValid(&why)) {
    why = "fpfh: " + why;
  } else if (method != CoarseMethod::kNone && !multi_start.IsValid(&why)) {
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
  if (options.method == CoarseMethod::kNone) {
    result.winner = "identity";
    return result;
  }
  std::vector<CoarseStart> starts;
  bool add_pca = options.method == CoarseMethod::kPca;
  if (options.method == CoarseMethod::kFpfh) {
    report(options.progress, "coarse: fpfh", 0.0);
    result.fpfh_used = true;
    result.fpfh = fpfh_ransac(scan, reference.points(), options.fpfh);
    report(options.progress, "coarse: fpfh", 1.0);
    if (result.fpfh.found) starts.push_back({"fpfh", result.fpfh.T_ref_scan});
    add_pca = !result.fpfh.found || result.fpfh.inlier_fraction < options.fpfh_trusted_fraction;
  }
  if (add_pca) {
    for (CoarseStart& s : pca_starts(scan, reference.points(), options.pca_ambiguity)) starts.push_back(std::move(s));
  }
  report(options.progress, "coarse: starts", 0.0);
  result.ranking = rank_starts(scan, reference, starts, options.multi_start);
  report(options.progress, "coarse: starts", 1.0);
  const StartReport& best = result.ranking.starts[static_cast<std::size_t>(result.ranking.best)];
  result.T_ref_scan = best.T_probe;
  result.winner = best.label;
  return result;
}

}  // namespace conform
