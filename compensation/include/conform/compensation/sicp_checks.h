#pragma once
// Can a Subdivision-ICP path be trusted? A robot cuts along it, so a plausible wrong path is the worst outcome. The
// checks measure what the registration itself shows (beyond the paper, which reports no such figures):
//   - noise: measured on the scan alone (plane fits over a few mm, estimate_surface_noise), so that a registration that
//     fits every segment badly cannot raise its own bar;
//   - edge support where the path runs: a row is measured when at least min_edge_points scan points lie within
//     edge_radius_mm of it. A stretch of unmeasured rows is bridged (its rows trusted, at a lower confidence) when it
//     is at most max_edge_gap_mm long, measured rows close it on both sides and no corner of the contour lies in it (or
//     within edge_radius_mm of its ends, where the corner is seen from one side only):
//     along a smooth stretch the blended transforms interpolate the measured ends, but a corner's place sets the path
//     on both sides of it, and an unmeasured corner is a guess (measured on the nose cone with 20% of the edge
//     unscanned: 0.02-0.22 mm off the path along bridged smooth stretches, up to 1.07 mm past an unscanned corner);
//   - blind segments: fewer edge (neighbourhood) scan points than min_edge_points (a warning: their rows are judged
//     by the edge support above); bare segments, without surface (stability) points either, make their rows untrusted;
//   - outlier segments: a residual RMS above outlier_ratio times the noise (the segment did not find the part);
//   - rows far from the contour: the segment transforms describe the part near the contour only;
//   - rows where the scanned surface departs from the model (sicp_surface_misfit.h): the structure of the residuals
//     near each row and against its neighbours, significant against the noise's standard error for the point count,
//     so that whether a local shape change (a dent) is caught does not hinge on the noise level.
// Each row gets a confidence in [0, 1] (its segments' blended confidence) and its correction split into the
// compensated row's frame: across the edge (in the surface), along the tool axis, along the path.
//
//   const SicpCheck c = check_sicp_path(contour, registration, nominal, compensated, SicpCheckOptions{});
//   if (!c.trusted) ...  // c.reason says why and what to change

#include <cstddef>
#include <string>
#include <vector>

#include "conform/compensation/sicp_surface_misfit.h"
#include "conform/compensation/trajectory.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/polyline.h"
#include "conform/registration/sicp.h"

namespace conform {

struct SicpCheckOptions {
  std::size_t min_edge_points = 10;  // edge (neighbourhood) scan points a segment needs to measure its rows; 0: any
  double outlier_ratio = 4.0;        // a segment's residual RMS above this times the noise is an outlier, > 1
  // The noise a segment's RMS is judged against is at least this, >= 0: a rigid segment's own misfit on a smoothly
  // deformed part does not fall with the scan's noise (up to 0.15 mm RMS on the new panels at 0.02-0.03 mm noise,
  // whose paths were 0.11-0.31 mm off at peak: refused before by 4 x the noise). Local shape changes are judged by
  // their structure instead (max_surface_offset_mm, max_normal_error_deg, max_local_offset_mm).
  double min_noise_mm = 0.05;
  // A segment with more than this share of its residuals off the surface (SicpSegmentFit::off_surface_share: beyond
  // 4 robust sigmas) has met a shape it cannot follow (a dent, a fixture), in (0, 1]; stray points are a percent.
  double max_off_surface = 0.05;
  double max_offset_mm = 10.0;     // rows farther than this from the nominal contour cannot be trusted, > 0
  double min_confidence = 0.5;     // a row below this confidence makes the path untrusted, in [0, 1]
  double edge_radius_mm = 10.0;    // scan points within this of a compensated row measure the edge there, > 0
  double max_edge_gap_mm = 150.0;  // the longest unmeasured stretch of path bridged from its measured ends, >= 0
  // An unmeasured stretch over a corner is bridged when it is at most this long and both sides are measured for 20 mm
  // or more next to it (they fix the corner), >= 0 (0: never).
  double max_corner_gap_mm = 40.0;
  // Where the scan shows its own edge (a scan of the face without the flank: SicpResult::scan_edge), a row whose
  // path lies farther than this across from it (the median over the edge points within edge_window_mm) is not
  // trusted, > 0.
  double max_edge_offset_mm = 0.5;
  double edge_window_mm = 5.0;
  // A row whose correction changes by more than this from the row before (per mm of nominal row spacing, at least
  // this), or that steps back along the path, is not trusted: a smooth deformation moves neighbouring rows alike
  // (the truth's steps on the generated panels: 0.01-0.06 mm per 1 mm row), > 0.
  double max_row_step_mm = 0.2;
  // Where the scanned surface departs from the model's near a row (sicp_surface_misfit.h; a dent, a bulge shorter
  // than a segment), the row is not trusted when one of these figures is beyond its limit and misfit_significance
  // standard errors (from the scan's noise and the point count) clear of zero, > 0 each: the scanned surface off
  // the model's along the tool axis at the row (the plane fitted within 6 mm); the tool normal off the scanned
  // surface's slope along the path; the mean residual within 4 mm of the row against the rows 8-16 mm before and
  // after it. Tuned on the new panels (docs/sicp.md): 100 undented paths (seeds 31-40, oval and cut-out, noise
  // 0.02-0.15 mm) reached 0.27 mm, 1.14 deg and 0.23 mm.
  double max_surface_offset_mm = 0.4;
  double max_normal_error_deg = 1.75;
  double max_local_offset_mm = 0.25;
  // A dent narrower than the plane's disc (the bump of sicp_surface_misfit.h): the row is not trusted where the
  // slope the fitted bump implies exceeds this (the bar's tool normals), significantly, > 0. The 150 undented paths
  // (plates and nose cones) reached 2.44 deg at 5 standard errors.
  double max_dent_slope_deg = 3.0;
  double misfit_significance = 5.0;
  bool IsValid(std::string* error) const;
};

struct SicpRowReport {
  // The correction (compensated - nominal position) in the compensated row's frame, mm: across the edge in the
  // surface (tool axis x path direction), along the tool axis, along the path.
  double across_mm = 0.0;
  double axis_mm = 0.0;
  double along_mm = 0.0;
  double confidence = 0.0;         // [0, 1]: 1 measured (edge scan at the row) by segments with residuals at the noise
  std::size_t edge_points = 0;     // scan points within edge_radius_mm of the compensated row, up to 2 min_edge_points
  double gap_mm = 0.0;             // length of the unmeasured stretch the row lies in (0: measured)
  double edge_offset_mm = 0.0;     // across, from the row to the scan's own edge (scan_edge) near it; 0 without
  double surface_offset_mm = 0.0;  // the scanned surface off the model's at the row, along the normal (misfit)
  double normal_error_deg = 0.0;   // the tool normal against the scanned surface's slope along the path (misfit)
  double local_offset_mm = 0.0;    // the mean residual near the row against its neighbours' (misfit)
  double dent_slope_deg = 0.0;     // the slope of a narrow dent fitted at the row (misfit; 0: none significant)
  bool misfit = false;             // one of the three beyond its limit, significantly
  // Measured, but with neither scan of the flank (misfit's flank_points) nor the scan's own edge near it: where the
  // edge lies across is not measured there (laser stripes along an edge without its flank).
  bool unanchored = false;
  double contour_distance_mm = 0.0;  // of the nominal row from the nominal contour
};

struct SicpCheck {
  double noise_mm = 0.0;                          // the scan's noise (or, without it, the median segment residual RMS)
  std::vector<std::size_t> blind_segments;        // fewer edge points than min_edge_points
  std::vector<std::size_t> bare_segments;         // no stability (surface) points either
  std::vector<std::size_t> outlier_segments;      // residual RMS > outlier_ratio * noise, or ICP not usable
  std::vector<std::size_t> off_surface_segments;  // more than max_off_surface of the residuals off the surface
  std::vector<double> segment_confidence;         // per segment, [0, 1]
  std::vector<SicpRowReport> rows;                // one per trajectory row
  std::size_t untrusted_rows = 0;                 // confidence below min_confidence
  std::size_t far_rows = 0;                       // farther than max_offset_mm from the contour
  std::size_t unmeasured_rows = 0;                // fewer than min_edge_points scan points within edge_radius_mm
  std::size_t bridged_rows = 0;                   // unmeasured, on a stretch bridged from its measured ends
  std::size_t off_edge_rows = 0;                  // farther than max_edge_offset_mm across from the scan's edge
  std::size_t jump_rows = 0;                      // correction jumped by more than max_row_step_mm, or stepped back
  std::size_t misfit_rows = 0;         // the scanned surface off the model's there (max_surface_offset_mm, ...)
  std::size_t unanchored_rows = 0;     // measured rows with neither flank nor the scan's own edge near them
  double max_surface_offset_mm = 0.0;  // the largest significant |surface_offset_mm| (0: none significant)
  double max_normal_error_deg = 0.0;   // the largest significant normal_error_deg
  double max_local_offset_mm = 0.0;    // the largest significant |local_offset_mm|
  double max_dent_slope_deg = 0.0;     // the largest significant dent_slope_deg
  double max_row_step_mm = 0.0;        // the largest change of the correction between consecutive rows
  double max_edge_offset_mm = 0.0;     // the largest |edge_offset_mm|
  double longest_gap_mm = 0.0;         // the longest unmeasured stretch of path
  double min_confidence = 0.0;
  bool trusted = false;  // the registration converged and every row has min_confidence
  std::string reason;    // when not trusted: why, and what to change
  std::vector<std::string> warnings;
};

// Scan points within radius_mm of each row of the compensated trajectory (the edge support where the path runs),
// counted up to cap (0: all; the checks need 2 min_edge_points at most).
std::vector<std::size_t> count_edge_points(const KdTree& scan, const Trajectory& compensated, double radius_mm,
                                           std::size_t cap = 0);

// registration: from sicp_register (segments empty for the rigid and projection models: rows are then judged by
// their distance from the contour only). nominal, compensated: same rows. Throws conform::Error for invalid options
// or trajectories of different lengths.
// scan_noise_mm: estimate_surface_noise (registration/surface_noise.h) of the scan the registration used (0: the
// median segment RMS stands in). row_edge_points: count_edge_points of that scan at the compensated rows (empty: a
// row counts the edge points of the segment whose core holds it). misfit: sicp_surface_misfit of the path (empty:
// not judged).
SicpCheck check_sicp_path(const Polyline& contour, const SicpResult& registration, const Trajectory& nominal,
                          const Trajectory& compensated, const SicpCheckOptions& options, double scan_noise_mm = 0.0,
                          const std::vector<std::size_t>& row_edge_points = {},
                          const std::vector<SicpRowMisfit>& misfit = {});

}  // namespace conform
