#include "start_screening.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "conform/core/parallel.h"
#include "conform/registration/icp.h"
#include "start_scoring.h"

namespace conform::detail {

std::vector<CoarseStart> screened_starts(const std::vector<CoarseStart>& shifted,
                                         const std::vector<Eigen::Vector3d>& few, const IcpReference& reference,
                                         const MultiStartOptions& options, double reach, double best_share,
                                         const PosesApart& apart) {
  std::vector<double> share(shifted.size(), -1.0);
  std::vector<Eigen::Isometry3d> landed(shifted.size(), Eigen::Isometry3d::Identity());
  for_each_in_parallel(shifted.size(), [&](std::size_t i) {
    IcpOptions quick = options.probe;
    quick.progress = nullptr;
    quick.max_iterations = options.wall_screen_iterations;
    const IcpResult r = icp(few, reference, shifted[i].T_ref_scan, quick);
    share[i] = share_of(inliers(few, r.T_ref_scan, reference, options.inlier_distance_mm, reach));
    landed[i] = r.T_ref_scan;
  });
  std::vector<std::size_t> order(shifted.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return share[a] > share[b]; });
  std::vector<CoarseStart> kept;
  std::vector<std::size_t> kept_index;
  for (std::size_t k = 0; k < shifted.size() && kept.size() < options.wall_probes; ++k) {
    const std::size_t i = order[k];
    if (share[i] < (1.0 - options.share_margin) * best_share) break;
    if (apart && std::any_of(kept_index.begin(), kept_index.end(),
                             [&](std::size_t j) { return !apart(landed[j], landed[i]); })) {
      continue;
    }
    kept.push_back(shifted[i]);
    kept_index.push_back(i);
  }
  return kept;
}

std::vector<CoarseStart> starts_to_probe(const std::vector<CoarseStart>& starts,
                                         const std::vector<Eigen::Vector3d>& few, const IcpReference& reference,
                                         const MultiStartOptions& options, double reach, const Eigen::Vector3d& centre,
                                         double size_mm) {
  std::vector<CoarseStart> given;
  std::vector<CoarseStart> to_screen;
  for (const CoarseStart& s : starts) (s.screen ? to_screen : given).push_back(s);
  if (to_screen.empty()) return given;
  std::vector<CoarseStart> kept;
  if (options.inlier_distance_mm > 0.0) {
    const double screen_mm = std::max(10.0 * options.inlier_distance_mm, 0.01 * size_mm);
    const double screen_rad = options.distinct_deg * M_PI / 180.0;
    kept = screened_starts(to_screen, few, reference, options, reach, 0.0,
                           [&](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
                             return rotation_angle(b * a.inverse()) > screen_rad ||
                                    (b * centre - a * centre).norm() > screen_mm;
                           });
  } else {
    const std::size_t stride =
        std::max<std::size_t>(1, to_screen.size() / std::max<std::size_t>(1, options.wall_probes));
    for (std::size_t i = 0; i < to_screen.size() && kept.size() < options.wall_probes; i += stride) {
      kept.push_back(to_screen[i]);
    }
  }
  given.insert(given.end(), kept.begin(), kept.end());
  return given;
}

}  // namespace conform::detail
