#pragma once
// The S-ICP path's checks against the scanned surface itself (compensation/sicp_checks.h): rows where the surface
// departs from the model's (a dent, a bulge), and rows that nothing measured holds across the edge.

#include <vector>

#include "conform/compensation/sicp_checks.h"
#include "conform/compensation/sicp_surface_misfit.h"
#include "conform/compensation/trajectory.h"

namespace conform::detail {

// Marks c.rows' misfit (and counts c.misfit_rows, the largest offsets and slopes) from each row's surface misfit,
// with a warning naming the stretches. Nothing for an empty misfit; throws conform::Error when its size is not the
// rows'.
void judge_misfit(const std::vector<SicpRowMisfit>& misfit, const Trajectory& t, const SicpCheckOptions& o,
                  SicpCheck& c);

// Marks c.rows' unanchored (and counts c.unanchored_rows) on stretches of measured rows without the flank's points
// or the scan's own edge near them (edge_seen) that are too long to bridge or at an open end, with a warning.
void judge_anchoring(const std::vector<SicpRowMisfit>& misfit, const std::vector<bool>& edge_seen, const Trajectory& t,
                     bool closed, SicpCheck& c);

}  // namespace conform::detail
