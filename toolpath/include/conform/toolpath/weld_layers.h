#pragma once
// Weld layers that refill eroded craters (Simas, Dias & Guenther; the ROBOTURB turbine-blade repair):
//   1. depth of the eroded surface below the reference at the eroded grid points (closest points, Newton) -> the
//      measurement noise (robust: 1.4826 x median absolute deviation) and which side of the reference is "inside";
//   2. the damaged area's boundary: the eroded surface intersected with the reference offset inward by a depth
//      threshold (default 6 x the noise, at least 0.01 mm; 0: the plain intersection), by recursive subdivision
//      (surface_intersection.h); the closed curves are the crater rims;
//   3. parallel paths at half the bead spacing dc/2 over the rims' parameter box (parallel_paths.h), from an
//      iso-parametric reference path along u, on the eroded grid smoothed by a few binomial passes (curvature, a
//      second derivative, would follow the noise and make the paths wiggle and loop);
//   4. layer k (1, 2, ...) takes the odd half-step paths when k is odd and the even ones when k is even, so the
//      beads of one layer sit between those of the one below; each path is clipped to where the point lies inside
//      a rim and the crater is still deeper than (k - 1) cd there; the layer lies (k - 1) cd above the eroded
//      surface along its outward normal.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/bezier_network.h"
#include "conform/toolpath/surface_intersection.h"

namespace conform {

struct WeldLayerOptions {
  double bead_spacing_mm = 0.0;     // dc: distance between neighbouring beads of a layer, mm; required
  double layer_height_mm = 0.0;     // cd: height of one layer, mm; required
  double chord_error_mm = 0.0;      // delta: max chord error of a path step, mm; required
  double torch_distance_mm = 0.0;   // w: torch-to-surface distance for Eq. (5), mm
  int layers = 0;                   // 0: enough to fill the deepest crater, ceil(max depth / cd)
  double depth_threshold_mm = -1.0; // < 0: 6 x the estimated noise (>= 0.01 mm); 0: plain intersection
  double intersection_tolerance_mm = 0.0;  // 0: dc / 10
  double max_step_mm = 0.0;                // 0: 2 dc
  int smoothing_passes = 3;                // binomial passes over the eroded grid for the paths (not the rims)

  bool IsValid(std::string* error) const;
};

struct WeldPath {
  int layer = 0;  // 1-based
  int path = 0;   // 1-based within its layer
  std::vector<Eigen::Vector3d> points;   // mm, on the layer ((k - 1) cd above the eroded surface)
  std::vector<Eigen::Vector3d> normals;  // outward unit normals (towards the torch)
  double length_mm() const;
};

struct WeldLayerResult {
  bool ok = false;
  std::string termination = "not run";
  double noise_mm = 0.0;            // estimated measurement noise (1 sigma)
  double depth_threshold_mm = 0.0;  // the one used
  bool threshold_estimated = false; // true when it came from the noise
  double max_depth_mm = 0.0;        // deepest eroded grid point below the reference
  std::vector<IntersectionCurve> rims;  // closed boundaries of the damaged area (on the eroded surface)
  std::size_t open_curves = 0;          // intersection curves that did not close (ignored)
  int layers = 0;
  std::size_t half_step_paths = 0;      // parallel paths at dc / 2 before clipping
  std::vector<WeldPath> paths;          // by layer, then along the stepping direction
  double total_length_mm = 0.0;
  double spacing_error_pct_max = 0.0;   // neighbouring half-step paths inside the rims vs their target g
  double chord_error_mm_max = 0.0;      // over every path step
  // Per layer: % of its region (inside the rims, deeper than (k - 1) cd) within 0.55 x the local bead spacing of
  // one of its paths (0 for a layer without paths), and the worst of them.
  std::vector<double> coverage_pct;
  double coverage_pct_min = 0.0;
  std::size_t loops_removed = 0;
  std::size_t newton_offsets = 0;
};

// Throws conform::Error when the options are not valid. ok = false (with the reason in termination) when no damage
// is found or no rim closes.
WeldLayerResult plan_weld_layers(const BezierNetwork& eroded, const BezierNetwork& reference,
                                 const WeldLayerOptions& options);

}  // namespace conform
