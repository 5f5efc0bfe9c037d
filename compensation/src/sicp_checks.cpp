#include "conform/compensation/sicp_checks.h"

#include <algorithm>
#include <cmath>

#include "conform/compensation/sicp_blend.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/median.h"
#include "conform/core/nearest_neighbors.h"

#include "path_closure.h"
#include "sicp_surface_checks.h"

namespace conform {
namespace {

std::string list(const std::vector<std::size_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size() && i < 12; ++i) s += (i > 0 ? ", " : "") + std::to_string(v[i]);
  return v.size() > 12 ? s + ", ..." : s;
}

// Per segment: blind, bare, outlier lists and a confidence from its residuals (1 at <= 2x noise; 0 for an outlier or
// a bare segment). Its edge data are judged row by row (judge_edge_support).
void judge_segments(const SicpResult& r, const SicpCheckOptions& o, double scan_noise_mm, SicpCheck& c) {
  std::vector<double> rms;
  for (const SicpSegmentFit& f : r.segments) {
    if (f.usable && f.neighbourhood_points >= o.min_edge_points) rms.push_back(f.rms_mm);
  }
  c.noise_mm = scan_noise_mm > 0.0 ? scan_noise_mm : (rms.empty() ? r.coarse.rms_mm : median(rms));
  const double noise = std::max({c.noise_mm, o.min_noise_mm, 1e-6});
  for (std::size_t k = 0; k < r.segments.size(); ++k) {
    const SicpSegmentFit& f = r.segments[k];
    const bool blind = f.neighbourhood_points < o.min_edge_points;
    const bool bare = blind && f.stability_points == 0;
    const bool off_surface = f.off_surface_share > o.max_off_surface;
    const bool outlier = !f.usable || f.rms_mm > o.outlier_ratio * noise || off_surface;
    if (blind) c.blind_segments.push_back(k);
    if (bare) c.bare_segments.push_back(k);
    if (outlier && !blind) c.outlier_segments.push_back(k);
    if (off_surface && !blind) c.off_surface_segments.push_back(k);
    const double fit = std::min(1.0, 2.0 * noise / std::max(f.rms_mm, 1e-9));
    c.segment_confidence.push_back(bare || (outlier && !blind) ? 0.0 : fit);
  }
}

// Is the contour's corner at arc length `corner` between the rows at arc lengths sa and sb (the short way round)?
bool corner_between(const ContourSegmentation& g, double sa, double sb, double corner) {
  if (!g.closed) return std::min(sa, sb) <= corner && corner <= std::max(sa, sb);
  const double d = g.ahead(sa, sb);
  return d <= 0.5 * g.length_mm ? g.ahead(sa, corner) <= d : g.ahead(sb, corner) <= g.length_mm - d;
}

double arc_distance(const ContourSegmentation& g, double a, double b) {
  return g.closed ? std::min(g.ahead(a, b), g.ahead(b, a)) : std::abs(a - b);
}

// The measured edge a corner's both sides need before a short unmeasured stretch over it is bridged.
constexpr double kCornerSideMm = 20.0;

// The warning for unmeasured rows that no bridge reaches, saying why (too long, over a corner, at an open end).
void warn_unbridged(const SicpCheckOptions& o, bool too_long, bool at_corner, bool at_end, SicpCheck& c) {
  const std::size_t unbridged = c.unmeasured_rows - c.bridged_rows;
  if (unbridged > 0) {
    std::string why = too_long ? "longer than " + format_fixed(o.max_edge_gap_mm, 0) + " mm" : "";
    if (at_corner) why += std::string(why.empty() ? "" : ", ") + "over a corner of the contour";
    if (at_end) why += std::string(why.empty() ? "" : ", ") + "at an open end";
    if (why.empty()) why = "no row of the path measured";
    c.warnings.push_back(std::to_string(unbridged) +
                         " rows lie on stretches of the path without scan of the edge that cannot be bridged from "
                         "measured rows (" +
                         why + "; longest stretch " + format_fixed(c.longest_gap_mm, 1) +
                         " mm): their place is a guess; scan the edge there (or accept guessed rows with a lower "
                         "minimum of edge points)");
  }
}

// The unmeasured stretches of the path (runs of rows with fewer than min_edge_points edge points): each row's
// stretch length, from the measured row before it to the one after (0 when measured), and whether it is bridged
// (closed by measured rows on both sides, at most max_edge_gap_mm long, no corner in it or within edge_radius_mm of
// its ends). Returns per row the factor
// of its confidence: the edge share when measured, 1 - gap / (2 max gap) when bridged, 0 otherwise.
std::vector<double> judge_edge_support(const std::vector<Eigen::Vector3d>& rows, bool closed,
                                       const ContourSegmentation& g, const std::vector<double>& s,
                                       const SicpCheckOptions& o, SicpCheck& c) {
  const std::size_t n = rows.size();
  const double needed = 2.0 * static_cast<double>(o.min_edge_points);
  std::vector<double> factor(n, 0.0);
  bool too_long = false, at_corner = false, at_end = false;  // why some stretch is not bridged
  std::vector<std::size_t> walk;  // row indices in path order, from a measured row on a closed path
  std::size_t start = 0;
  while (closed && start < n && c.rows[start].edge_points < o.min_edge_points) ++start;
  if (start == n) start = 0;
  for (std::size_t k = 0; k < n; ++k) walk.push_back((start + k) % n);
  const auto measured = [&](std::size_t i) { return c.rows[i].edge_points >= o.min_edge_points; };
  for (std::size_t w = 0; w < n;) {
    if (measured(walk[w])) {
      const std::size_t i = walk[w++];
      factor[i] = needed > 0.0 ? std::min(1.0, static_cast<double>(c.rows[i].edge_points) / needed) : 1.0;
      continue;
    }
    std::size_t end = w;  // the run walk[w, end)
    while (end < n && !measured(walk[end])) ++end;
    const bool before = w > 0, after = end < n || (closed && measured(walk[0]));
    const std::size_t first = before ? w - 1 : w, last = end < n ? end : (after ? n : n - 1);
    double gap = 0.0;
    bool corner = false;
    for (std::size_t k = first; k < last; ++k) {
      const std::size_t a = walk[k], b = walk[(k + 1) % n];
      gap += (rows[b] - rows[a]).norm();
      for (int p : g.corners)
        corner = corner || corner_between(g, s[a], s[b], g.arc_length_mm[static_cast<std::size_t>(p)]);
    }
    // A corner within edge_radius_mm past a measured end is seen from one side only (nose cone, 20% unscanned,
    // seed 11: 0.55 mm off the path there; seed 3 full size: 0.47 mm).
    for (int p : g.corners) {
      const double at = g.arc_length_mm[static_cast<std::size_t>(p)];
      for (std::size_t end_row : {walk[first], walk[last % n]})
        corner = corner || arc_distance(g, s[end_row], at) <= o.edge_radius_mm;
    }
    // A corner is bridged only over a short stretch whose both sides are measured for at least kCornerSideMm: the two
    // measured sides then fix where they meet (a 30 mm occlusion over a 6 mm corner: 0.08 mm off the path; a 117 mm
    // stretch past a corner: up to 1.07 mm).
    const auto measured_arc = [&](std::size_t from, int direction) {
      double arc = 0.0;
      for (std::size_t k = from, steps = 0; steps < n && arc < kCornerSideMm; ++steps) {
        const std::size_t next = (k + n + static_cast<std::size_t>(direction)) % n;
        if (!closed && ((direction < 0 && k == 0) || (direction > 0 && k + 1 == n))) break;
        if (!measured(walk[next])) break;
        arc += (rows[walk[next]] - rows[walk[k]]).norm();
        k = next;
      }
      return arc;
    };
    const bool corner_fixed = before && after && gap <= o.max_corner_gap_mm &&
                              measured_arc(first, -1) >= kCornerSideMm && measured_arc(last % n, +1) >= kCornerSideMm;
    const bool bridged = before && after && gap <= o.max_edge_gap_mm && (!corner || corner_fixed);
    too_long = too_long || (!bridged && gap > o.max_edge_gap_mm);
    at_corner = at_corner || (!bridged && corner);
    at_end = at_end || (!closed && (!before || !after));
    for (std::size_t k = w; k < end; ++k) {
      c.rows[walk[k]].gap_mm = gap;
      factor[walk[k]] = bridged ? 1.0 - 0.5 * gap / std::max(o.max_edge_gap_mm, 1e-9) : 0.0;
    }
    c.unmeasured_rows += end - w;
    if (bridged) c.bridged_rows += end - w;
    c.longest_gap_mm = std::max(c.longest_gap_mm, gap);
    w = end;
  }
  warn_unbridged(o, too_long, at_corner, at_end, c);
  return factor;
}

// The correction of row i split along the compensated row's tool axis, path direction and the cross direction.
void split_correction(const Trajectory& nominal, const Trajectory& t, std::size_t i, bool closed, SicpRowReport& row) {
  const std::size_t n = t.points.size();
  const Eigen::Vector3d d = t.points[i] - nominal.points[i];
  const Eigen::Vector3d& axis = t.normals[i];
  const std::size_t next = i + 1 < n ? i + 1 : (closed ? 0 : n - 1);
  const std::size_t previous = i > 0 ? i - 1 : (closed ? n - 1 : 0);
  Eigen::Vector3d tangent = t.points[next] - t.points[previous];
  tangent -= tangent.dot(axis) * axis;
  row.axis_mm = d.dot(axis);
  if (tangent.norm() < 1e-12) return;
  tangent.normalize();
  row.along_mm = d.dot(tangent);
  row.across_mm = d.dot(axis.cross(tangent));
}

// Each row's distance across the edge from the scan's own edge points (SicpResult::scan_edge) within the window: the
// median, in the surface, perpendicular to the path. A row farther than max_edge_offset_mm loses its confidence.
std::vector<bool> judge_edge_offset(const std::vector<Eigen::Vector3d>& scan_edge, const Trajectory& t, bool closed,
                                    const SicpCheckOptions& o, SicpCheck& c) {
  std::vector<bool> seen(t.points.size(), false);
  if (scan_edge.empty()) return seen;
  const KdTree tree(scan_edge);
  std::vector<int> indices;
  std::vector<float> sq;
  const std::size_t n = t.points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t next = i + 1 < n ? i + 1 : (closed ? 0 : n - 1);
    const std::size_t previous = i > 0 ? i - 1 : (closed ? n - 1 : 0);
    Eigen::Vector3d tangent = t.points[next] - t.points[previous];
    tangent -= tangent.dot(t.normals[i]) * t.normals[i];
    if (tangent.norm() < 1e-12) continue;
    const Eigen::Vector3d across = t.normals[i].cross(tangent.normalized());
    tree.radius(t.points[i].cast<float>(), static_cast<float>(o.edge_window_mm), indices, sq);
    if (indices.size() < 5) continue;
    seen[i] = true;
    std::vector<double> offsets;
    for (int k : indices) offsets.push_back((scan_edge[static_cast<std::size_t>(k)] - t.points[i]).dot(across));
    const double offset = median(offsets);
    c.rows[i].edge_offset_mm = offset;
    c.max_edge_offset_mm = std::max(c.max_edge_offset_mm, std::abs(offset));
    if (std::abs(offset) > o.max_edge_offset_mm) ++c.off_edge_rows;
  }
  if (c.off_edge_rows > 0)
    c.warnings.push_back(std::to_string(c.off_edge_rows) + " rows lie more than " +
                         format_fixed(o.max_edge_offset_mm, 2) + " mm across from where the scan's face ends (up to " +
                         format_fixed(c.max_edge_offset_mm, 2) +
                         " mm): the registration did not find the edge there; scan the opening's flank, or more "
                         "densely along the edge");
  return seen;
}

// Rows whose correction jumps from the row before (more than max_row_step_mm per mm of nominal spacing, at least
// max_row_step_mm) or that step back along the path: both rows of the pair lose their confidence.
std::vector<bool> judge_row_steps(const Trajectory& nominal, const Trajectory& t, bool closed,
                                  const SicpCheckOptions& o, SicpCheck& c) {
  const std::size_t n = t.points.size();
  std::vector<bool> jump(n, false);
  double worst_back = 0.0;
  for (std::size_t i = closed ? 0 : 1; i < n; ++i) {
    const std::size_t h = i > 0 ? i - 1 : n - 1;
    const Eigen::Vector3d step_nominal = nominal.points[i] - nominal.points[h];
    const double spacing = step_nominal.norm();
    if (spacing < 1e-9) continue;
    const double change = ((t.points[i] - nominal.points[i]) - (t.points[h] - nominal.points[h])).norm();
    const double forward = (t.points[i] - t.points[h]).dot(step_nominal) / spacing;
    c.max_row_step_mm = std::max(c.max_row_step_mm, change);
    if (change > o.max_row_step_mm * std::max(1.0, spacing) || forward <= 0.0) {
      jump[i] = jump[h] = true;
      if (forward <= 0.0) worst_back = std::max(worst_back, -forward);
    }
  }
  for (bool j : jump) c.jump_rows += j ? 1 : 0;
  if (c.jump_rows > 0)
    c.warnings.push_back(std::to_string(c.jump_rows) + " rows jump: their correction changes by up to " +
                         format_fixed(c.max_row_step_mm, 3) + " mm from one row to the next (more than " +
                         format_fixed(o.max_row_step_mm, 2) + " mm per mm of row spacing)" +
                         (worst_back > 0.0
                              ? ", or they step back along the path (up to " + format_fixed(worst_back, 3) + " mm)"
                              : std::string()) +
                         ": check that the contour's closure and spacing match the trajectory");
  return jump;
}

// The warnings of blind, bare and outlier segments and far rows, each saying what to change.
void add_warnings(const SicpCheckOptions& o, std::size_t segments, SicpCheck& c) {
  if (!c.blind_segments.empty())
    c.warnings.push_back(std::to_string(c.blind_segments.size()) + " of " + std::to_string(segments) +
                         " segments have fewer than " + std::to_string(o.min_edge_points) +
                         " scan points near the edge (segments " + list(c.blind_segments) +
                         "): their rows are judged by the scan near each row");
  if (!c.bare_segments.empty())
    c.warnings.push_back(std::to_string(c.bare_segments.size()) + " segments have no scan data at all (segments " +
                         list(c.bare_segments) + ")");
  if (!c.outlier_segments.empty())
    c.warnings.push_back(
        std::to_string(c.outlier_segments.size()) + " segments fit the scan far worse than the others " +
        "(RMS above " + format_fixed(o.outlier_ratio, 1) + " x the noise " +
        format_fixed(std::max(c.noise_mm, o.min_noise_mm), 4) + " mm; segments " + list(c.outlier_segments) +
        "): check the scan there (spurious points, fixtures) or the nominal surface");
  if (!c.off_surface_segments.empty())
    c.warnings.push_back(std::to_string(c.off_surface_segments.size()) + " segments have more than " +
                         format_fixed(100.0 * o.max_off_surface, 0) +
                         "% of their scan points off the surface they were fitted to (segments " +
                         list(c.off_surface_segments) +
                         "): a local shape change there (a dent, a bulge, a fixture) that a rigid segment cannot "
                         "follow; check the part there");
  if (c.far_rows > 0)
    c.warnings.push_back(std::to_string(c.far_rows) + " trajectory rows lie more than " +
                         format_fixed(o.max_offset_mm, 1) +
                         " mm from the contour: the segments describe the part near the contour only; check that the "
                         "trajectory and the contour are in the same frame and units");
}

}  // namespace

bool SicpCheckOptions::IsValid(std::string* error) const {
  const char* why = nullptr;
  if (!std::isfinite(outlier_ratio) || outlier_ratio <= 1.0)
    why = "outlier ratio must be > 1";
  else if (!std::isfinite(min_noise_mm) || min_noise_mm < 0.0)
    why = "the least noise a segment's RMS is judged against must be >= 0 mm";
  else if (!std::isfinite(max_offset_mm) || max_offset_mm <= 0.0)
    why = "largest trajectory offset from the contour must be > 0 mm";
  else if (!std::isfinite(min_confidence) || min_confidence < 0.0 || min_confidence > 1.0)
    why = "minimum row confidence must be in [0, 1]";
  else if (!std::isfinite(edge_radius_mm) || edge_radius_mm <= 0.0)
    why = "edge radius must be > 0 mm";
  else if (!std::isfinite(max_edge_gap_mm) || max_edge_gap_mm < 0.0)
    why = "largest bridged gap of the edge scan must be >= 0 mm";
  else if (!std::isfinite(max_corner_gap_mm) || max_corner_gap_mm < 0.0)
    why = "largest bridged gap over a corner must be >= 0 mm";
  else if (!std::isfinite(max_edge_offset_mm) || max_edge_offset_mm <= 0.0)
    why = "largest offset of the path from the scan's edge must be > 0 mm";
  else if (!std::isfinite(edge_window_mm) || edge_window_mm <= 0.0)
    why = "edge window must be > 0 mm";
  else if (!std::isfinite(max_off_surface) || max_off_surface <= 0.0 || max_off_surface > 1.0)
    why = "largest share of a segment's points off the surface must be in (0, 1]";
  else if (!std::isfinite(max_row_step_mm) || max_row_step_mm <= 0.0)
    why = "largest step of the correction between rows must be > 0 mm";
  else if (!std::isfinite(max_surface_offset_mm) || max_surface_offset_mm <= 0.0)
    why = "largest offset of the scanned surface from the model must be > 0 mm";
  else if (!std::isfinite(max_normal_error_deg) || max_normal_error_deg <= 0.0)
    why = "largest tool normal error must be > 0 deg";
  else if (!std::isfinite(max_dent_slope_deg) || max_dent_slope_deg <= 0.0)
    why = "the dent slope limit must be > 0 deg";
  else if (!std::isfinite(max_local_offset_mm) || max_local_offset_mm <= 0.0)
    why = "largest local offset of the scanned surface must be > 0 mm";
  else if (!std::isfinite(misfit_significance) || misfit_significance <= 0.0)
    why = "misfit significance must be > 0 standard errors";
  if (why == nullptr) return true;
  if (error != nullptr) *error = why;
  return false;
}

std::vector<std::size_t> count_edge_points(const KdTree& scan, const Trajectory& compensated, double radius_mm,
                                           std::size_t cap) {
  std::vector<std::size_t> counts;
  std::vector<int> indices;
  std::vector<float> sq;
  const auto r2 = static_cast<float>(radius_mm * radius_mm);
  for (const Eigen::Vector3d& p : compensated.points) {
    if (cap == 0) {
      scan.radius(p.cast<float>(), static_cast<float>(radius_mm), indices, sq);
    } else {  // the cap nearest points only: a few tens instead of the hundreds within the radius
      scan.knn(p.cast<float>(), static_cast<int>(cap), indices, sq);
      sq.erase(std::remove_if(sq.begin(), sq.end(), [r2](float d) { return d > r2; }), sq.end());
    }
    counts.push_back(cap == 0 ? indices.size() : sq.size());
  }
  return counts;
}

SicpCheck check_sicp_path(const Polyline& contour, const SicpResult& r, const Trajectory& nominal,
                          const Trajectory& compensated, const SicpCheckOptions& o, double scan_noise_mm,
                          const std::vector<std::size_t>& row_edge_points, const std::vector<SicpRowMisfit>& misfit) {
  std::string why;
  if (!o.IsValid(&why)) throw Error("S-ICP checks: " + why);
  if (nominal.points.size() != compensated.points.size() || compensated.normals.size() != compensated.points.size())
    throw Error("S-ICP checks: the compensated trajectory's rows differ from the nominal one's");
  SicpCheck c;
  judge_segments(r, o, scan_noise_mm, c);
  const ContourSegmentation& g = r.segmentation;
  const bool by_segments = !r.segments.empty() && r.segments.size() == g.segments.size();
  std::vector<double> distances;
  const std::vector<double> s = locate_on_contour(
      contour, g.arc_length_mm.size() == contour.points.size() ? g.arc_length_mm : arc_lengths(contour), nominal.points,
      &distances);
  c.rows.resize(nominal.points.size());
  // A closed path (its ends within three median row spacings) wraps for the path direction at its ends.
  const bool closed = detail::rows_close(nominal.points);
  if (!row_edge_points.empty() && row_edge_points.size() != nominal.points.size())
    throw Error("S-ICP checks: the edge point counts differ from the trajectory's rows");
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    SicpRowReport& row = c.rows[i];
    split_correction(nominal, compensated, i, closed, row);
    row.contour_distance_mm = distances[i];
    if (!row_edge_points.empty())
      row.edge_points = row_edge_points[i];
    else if (by_segments)
      row.edge_points = r.segments[g.core_at(s[i])].neighbourhood_points;
  }
  const std::vector<double> support =
      by_segments ? judge_edge_support(nominal.points, closed, g, s, o, c) : std::vector<double>(c.rows.size(), 1.0);
  const std::vector<bool> edge_seen = judge_edge_offset(r.scan_edge, compensated, closed, o, c);
  const std::vector<bool> jumps = judge_row_steps(nominal, compensated, closed, o, c);
  detail::judge_misfit(misfit, compensated, o, c);
  detail::judge_anchoring(misfit, edge_seen, compensated, closed, c);
  c.min_confidence = 1.0;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    SicpRowReport& row = c.rows[i];
    row.confidence = support[i];
    // The lower of the edge support and the segments' fit, not their product: each rule refuses on its own terms
    // (a segment below half confidence is an outlier, a bridge below half is too long), and two passes do not add up
    // to a refusal (a 30 mm occlusion over a corner, bridged at about 0.9, beside a corner segment whose fit was just
    // above 0.5: their product 0.49, refused, 0.25 mm at peak).
    if (by_segments) {
      const BlendAt b = blend_at(g, s[i]);
      row.confidence = std::min(row.confidence, (1.0 - b.weight) * c.segment_confidence[b.segment] +
                                                    b.weight * c.segment_confidence[b.next]);
    }
    if (row.contour_distance_mm > o.max_offset_mm) row.confidence = 0.0, ++c.far_rows;
    if (std::abs(row.edge_offset_mm) > o.max_edge_offset_mm || jumps[i] || row.misfit || row.unanchored)
      row.confidence = 0.0;
    if (row.confidence < o.min_confidence) ++c.untrusted_rows;
    c.min_confidence = std::min(c.min_confidence, row.confidence);
  }
  add_warnings(o, r.segments.size(), c);
  c.trusted = r.converged && c.untrusted_rows == 0;
  if (!r.converged)
    c.reason = "the registration did not converge (" + r.termination + ")";
  else if (c.untrusted_rows > 0)
    c.reason = std::to_string(c.untrusted_rows) + " of " + std::to_string(c.rows.size()) +
               " rows have a confidence below " + format_fixed(o.min_confidence, 2) + " (" +
               (c.far_rows > 0                       ? "rows far from the contour"
                : c.off_edge_rows > 0                ? "rows away from the scan's edge"
                : c.jump_rows > 0                    ? "rows that jump"
                : c.misfit_rows > 0                  ? "rows where the scanned surface departs from the model"
                : c.unanchored_rows > 0              ? "rows without scan of the flank or of the face's end"
                : c.unmeasured_rows > c.bridged_rows ? "rows without scan of the edge that cannot be bridged"
                                                     : "segments fitting badly or without data") +
               "; see the warnings)";
  return c;
}

}  // namespace conform
