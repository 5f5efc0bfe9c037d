#pragma once
// Quick probes that pick, from many candidate starts (a thin wall's shifts, a long part's slides, a tube's turns
// about its axis: CoarseStart::screen), the few that rank_starts (multi_start.h) probes in full.

#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "conform/registration/coarse_pca.h"
#include "conform/registration/icp_reference.h"
#include "conform/registration/multi_start.h"

namespace conform::detail {

// Whether two poses are different answers.
using PosesApart = std::function<bool(const Eigen::Isometry3d&, const Eigen::Isometry3d&)>;

// The shifted starts worth a full probe, best first: each screened by a quick probe (wall_screen_iterations steps on
// `few` points; where its ICP lands decides, not the start itself: a scan a wall off is often turned a few degrees as
// well, and the start's own share is near 0), the wall_probes best by inlier share within share_margin of
// `best_share` (the best pose's on the same points): none when the right pose was already found. `reach`: as for
// inliers (start_scoring.h). With `apart` (slides: many shifts land on one pose), a start is kept only where its quick
// probe lands apart from those of the starts kept before it.
std::vector<CoarseStart> screened_starts(const std::vector<CoarseStart>& shifted,
                                         const std::vector<Eigen::Vector3d>& few, const IcpReference& reference,
                                         const MultiStartOptions& options, double reach, double best_share,
                                         const PosesApart& apart = nullptr);

// The starts given, those marked for screening (CoarseStart::screen: a tube's fine turns about its axis) screened by
// a quick probe each on `few`: of the wall_probes best by share, those whose quick probes land apart (distinct_deg,
// or 10 inlier distances and 1 % of the scan's size `size_mm` at its centre) are probed with the rest. Without
// inlier scoring, wall_probes of them evenly spread.
std::vector<CoarseStart> starts_to_probe(const std::vector<CoarseStart>& starts,
                                         const std::vector<Eigen::Vector3d>& few, const IcpReference& reference,
                                         const MultiStartOptions& options, double reach, const Eigen::Vector3d& centre,
                                         double size_mm);

}  // namespace conform::detail
