#include "sicp_surface_checks.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "conform/core/csv.h"
#include "conform/core/error.h"

namespace conform::detail {

namespace {

// judge_anchoring's flank and bridge (sicp_surface_checks.h).
constexpr std::size_t kMinFlankPoints = 3;
constexpr double kMaxUnheldMm = 20.0;

}  // namespace

// Rows where the scanned surface departs from the model's (sicp_surface_misfit): the fitted offset along the tool
// axis, the tool normal's error along the path or the local mean residual against the neighbours' beyond its limit,
// and misfit_significance standard errors clear of zero. The warning names the stretches (rows, length).
void judge_misfit(const std::vector<SicpRowMisfit>& misfit, const Trajectory& t, const SicpCheckOptions& o,
                  SicpCheck& c) {
  if (misfit.empty()) return;
  if (misfit.size() != c.rows.size())
    throw Error("S-ICP checks: the surface misfit differs from the trajectory's rows");
  const double k = o.misfit_significance;
  for (std::size_t i = 0; i < misfit.size(); ++i) {
    const SicpRowMisfit& m = misfit[i];
    SicpRowReport& row = c.rows[i];
    const bool dent = m.dent_z > k;
    if (dent) {
      row.dent_slope_deg = m.dent_slope_deg;
      c.max_dent_slope_deg = std::max(c.max_dent_slope_deg, m.dent_slope_deg);
      row.misfit = m.dent_slope_deg > o.max_dent_slope_deg;
    }
    if (m.points == 0) {
      if (row.misfit) ++c.misfit_rows;
      continue;
    }
    row.surface_offset_mm = m.offset_mm;
    row.normal_error_deg = m.along_error_deg;
    row.local_offset_mm = m.local_offset_mm;
    const bool offset = std::abs(m.offset_mm) > k * m.offset_se_mm;
    const bool tilt = m.along_z > k;
    const bool local = m.local_offset_se_mm > 0.0 && std::abs(m.local_offset_mm) > k * m.local_offset_se_mm;
    if (offset) c.max_surface_offset_mm = std::max(c.max_surface_offset_mm, std::abs(m.offset_mm));
    if (tilt) c.max_normal_error_deg = std::max(c.max_normal_error_deg, m.along_error_deg);
    if (local) c.max_local_offset_mm = std::max(c.max_local_offset_mm, std::abs(m.local_offset_mm));
    row.misfit = row.misfit || (offset && std::abs(m.offset_mm) > o.max_surface_offset_mm) ||
                 (tilt && m.along_error_deg > o.max_normal_error_deg) ||
                 (local && std::abs(m.local_offset_mm) > o.max_local_offset_mm);
    if (row.misfit) ++c.misfit_rows;
  }
  if (c.misfit_rows == 0) return;
  std::string stretches;
  std::size_t count = 0;
  for (std::size_t i = 0; i < c.rows.size();) {
    if (!c.rows[i].misfit) {
      ++i;
      continue;
    }
    std::size_t end = i;
    double arc = 0.0;
    while (end + 1 < c.rows.size() && c.rows[end + 1].misfit) arc += (t.points[end + 1] - t.points[end]).norm(), ++end;
    if (++count <= 4)
      stretches += std::string(count > 1 ? "; " : "") + "rows " + std::to_string(i) + "-" + std::to_string(end) + " (" +
                   format_fixed(arc, 0) + " mm)";
    i = end + 1;
  }
  if (count > 4) stretches += "; " + std::to_string(count - 4) + " more";
  c.warnings.push_back(
      std::to_string(c.misfit_rows) + " rows lie where the scanned surface departs from the fitted model (" +
      stretches + "): up to " + format_fixed(c.max_surface_offset_mm, 2) + " mm off along the tool axis (limit " +
      format_fixed(o.max_surface_offset_mm, 2) + "), " + format_fixed(c.max_local_offset_mm, 2) +
      " mm against the neighbouring rows (limit " + format_fixed(o.max_local_offset_mm, 2) + "), tool normals up to " +
      format_fixed(c.max_normal_error_deg, 1) + " deg off along the path (limit " +
      format_fixed(o.max_normal_error_deg, 2) + "), a narrow dent sloping up to " +
      format_fixed(c.max_dent_slope_deg, 1) + " deg (limit " + format_fixed(o.max_dent_slope_deg, 2) +
      "): a local shape change shorter than a segment (a dent, a bulge) that the path does not follow; inspect the "
      "part there and program that stretch from its own measurement");
}

// A measured row is held across the edge by the flank's scan points near it (kMinFlankPoints within the misfit's
// disc) or by the scan's own edge (edge_seen); with neither, the segments carry their across position in from where
// the edge was seen. A stretch of such rows up to kMaxUnheldMm long between held rows is bridged; a longer one, or
// one at an open end, is not. Laser stripes along an edge without its flank left 35 of 162 undented paths trusted
// 0.65-4 mm off at peak; the shortest such stretch on a path beyond the bar was 27.5 mm, the longest on a path
// within it 100 mm, so no length separates them and the bridge stays short (docs/measurements/sicp.md). Unmeasured
// rows are judged by their own bridge.
void judge_anchoring(const std::vector<SicpRowMisfit>& misfit, const std::vector<bool>& edge_seen, const Trajectory& t,
                     bool closed, SicpCheck& c) {
  const std::size_t n = c.rows.size();
  if (misfit.size() != n || n < 2) return;
  std::vector<bool> unheld(n);
  std::size_t held = 0;
  for (std::size_t i = 0; i < n; ++i) {
    unheld[i] = c.rows[i].gap_mm == 0.0 && misfit[i].flank_points < kMinFlankPoints && !edge_seen[i];
    if (!unheld[i]) ++held;
  }
  if (held == n) return;
  // Runs of unheld rows, walked from a held row (a closed path wraps); none held: one run, not bridged.
  std::size_t origin = 0;
  while (closed && origin < n && unheld[origin]) ++origin;
  if (origin == n) origin = 0;
  double longest = 0.0;
  for (std::size_t k = 0; k < n;) {
    const std::size_t i = (origin + k) % n;
    if (!unheld[i]) {
      ++k;
      continue;
    }
    std::vector<std::size_t> run{i};
    double arc = 0.0;
    while (run.size() < n) {
      const std::size_t next = (run.back() + 1) % n;
      if (!closed && next == 0) break;
      if (!unheld[next]) break;
      arc += (t.points[next] - t.points[run.back()]).norm();
      run.push_back(next);
    }
    const bool at_end = !closed && (run.front() == 0 || run.back() + 1 == n);
    longest = std::max(longest, arc);
    if (held == 0 || at_end || arc > kMaxUnheldMm) {
      for (std::size_t r : run) c.rows[r].unanchored = true;
      c.unanchored_rows += run.size();
    }
    k += run.size();
  }
  if (c.unanchored_rows == 0) return;
  c.warnings.push_back(std::to_string(c.unanchored_rows) +
                       " rows have no scan of the opening's flank and no end of the scanned face near them, on "
                       "stretches too long to bridge (longest " + format_fixed(longest, 0) + " mm, at most " +
                       format_fixed(kMaxUnheldMm, 0) + "): where the edge lies across is not measured there; scan "
                       "the flank (laser stripes across the edge, not along it)");
}

}  // namespace conform::detail
