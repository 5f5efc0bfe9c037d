#pragma once
// From the validated intersection graph to the path a tool follows, in the stub frame S (z along the stub axis):
// the vertices ordered by stub azimuth (Lind & Ystgaard 2020, Algorithm 1), optionally smoothed by a closed cubic
// smoothing B-spline, and resampled at equal azimuth steps (their Eq. 2) or, beyond the paper, at equal arc-length
// steps (homogeneous along the curve even where the azimuth runs fast or slow: radius ratios near 1, large offsets).
// Azimuth phi is measured about z_S from x_S (the toe, phi = 0) towards y_S.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/toolpath/intersection/intersection_graph.h"

namespace conform {

struct AzimuthOrder {
  CurveCheck check;                     // ok, or the failed condition (1h), [axis], [azimuth], [jordan] and where
  std::vector<Eigen::Vector3d> points;  // one turn, the first at the smallest azimuth in [0, 2 pi)
  std::vector<double> azimuth_rad;      // unwrapped, strictly increasing, azimuth_rad[0] in [0, 2 pi)
  std::size_t dropped = 0;              // vertices dropped as backtracking within the tolerance
  std::size_t merged = 0;               // coincident neighbours merged (zero-length edges, (1h))
  double max_backtrack_mm = 0.0;        // the largest backtrack let pass (arc on the stub), mm
  bool smoothed = false;                // the cycle was smoothed before the azimuth test
  double smoothing_rms_mm = 0.0;        // RMS distance of the cycle's vertices from the spline
};

struct AzimuthOrderOptions {
  // A vertex behind the azimuth reached so far by at most this (arc on the stub, mm) is dropped (scanner noise where
  // the surfaces cross at a shallow angle); farther behind fails [azimuth].
  double backtrack_tolerance_mm = 0.05;
  // >= 0: the cycle is smoothed first (closed smoothing cubic B-spline over chord length, target sum of squared
  // residuals in mm^2, fitting/bspline_fit.h) and the azimuth test runs on the smoothed curve; < 0: none.
  double smoothing_mm2 = -1.0;

  bool IsValid(std::string* error) const;
};

// Algorithm 1, made robust: walk the graph's cycle from the vertex of smallest azimuth; the direction is the one in
// which the curve winds positively about z (its winding number; [jordan] unless it is +-1); then unwrap the azimuth
// along the walk, dropping vertices that run back within the tolerance. The graph must be one cycle (it has passed
// select_main_curve / check_intersection_graph). Throws conform::Error for invalid options.
AzimuthOrder order_by_azimuth(const IntersectionGraph& graph, const AzimuthOrderOptions& options);
AzimuthOrder order_by_azimuth(const IntersectionGraph& graph, double backtrack_tolerance_mm = 0.05);

enum class PathSpacing { kAzimuth, kArcLength };

struct PathSamplingOptions {
  PathSpacing spacing = PathSpacing::kAzimuth;
  double step_rad = 0.017453292519943295;  // azimuth step (kAzimuth), rad, in (0, pi/2]; default 1 deg
  double step_mm = 5.0;                    // arc-length step (kArcLength), mm, > 0
  // Closed smoothing cubic B-spline over the ordered points before resampling (fitting/bspline_fit.h): the target
  // sum of squared residuals, mm^2 (scipy splprep's s; about n sigma^2 for noise sigma on n points). < 0: no
  // smoothing, the resampling interpolates the intersection polyline linearly (Eq. 2).
  double smoothing_mm2 = -1.0;
  // > 0: instead of smoothing_mm2, the target is n * smoothing_rms_mm^2 for the n ordered points (the noise you
  // expect on each intersection point, mm).
  double smoothing_rms_mm = 0.0;

  bool IsValid(std::string* error) const;
};

struct SampledPath {
  CurveCheck check;                     // the smoothed curve is checked for (1h) again
  std::vector<double> phi_rad;          // azimuth of each point, [0, 2 pi), increasing; the first is 0 (the toe)
  std::vector<Eigen::Vector3d> points;  // mm
  double length_mm = 0.0;               // of the closed polyline
  double max_step_mm = 0.0;             // between consecutive points, the closing step included
  double min_step_mm = 0.0;
  bool smoothed = false;
  double smoothing_rms_mm = 0.0;  // RMS distance of the ordered points from the spline
};

// Throws conform::Error when the options are invalid or the order has fewer than 3 points.
SampledPath sample_path(const AzimuthOrder& order, const PathSamplingOptions& options);

}  // namespace conform
