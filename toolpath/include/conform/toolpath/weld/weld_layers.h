#pragma once
// Weld layers that refill eroded craters (Simas, Dias & Guenther; the ROBOTURB turbine-blade repair):
//   1. the damage map (damage_map.h): depth of every eroded grid node below the reference, registration bias (offset,
//      tilt: a failure unless removed or kept on purpose), noise from local residuals, the damage side by volume, the
//      damaged regions (connected nodes deeper than the threshold): every crater, at the border or not;
//   2. the rims (paper, section 2): the eroded surface intersected with the reference offset inward by the threshold,
//      by recursive subdivision from a box tree (surface_intersection.h); a rim may be closed, or closed along the
//      grid's border; a region that no rim bounds is a dropped crater (not ok);
//   3. per region and layer k, on that layer's own surface (the eroded nodes lifted (k - 1) cd along the reference's
//      outward normal: a vertical fill, which does not focus in deep craters as a lift along the eroded normal does),
//      parallel paths at dc/2 (parallel_paths.h, Eq. 1-9) from an iso-parametric line dc/2 before the region, on the
//      layer surface smoothed by a few binomial passes (Eq. 5 needs curvature, which the noise would dominate);
//   4. layer k takes the odd half-step paths when k is odd and the even ones when k is even; each is clipped along
//      its curve (densely, not at its step points) to where the layer's remaining depth exceeds the threshold, cusps
//      are cut, and the pieces are re-stepped by Eq. (1) on the unsmoothed layer surface, where the points lie and the
//      chord error is measured;
//   5. coverage against the damage: the share of the damaged nodes within half a bead width of a layer-1 path (the
//      bead width on the surface: an option, dc by default), in all and per crater; overlap: the length of each
//      layer's paths within half a bead of another path of the layer (beads over beads), against max_overlap_mm.
// The paths are planned on the layer's surface at g = dc / 2 between half-step paths whatever the torch distance:
// Eq. (5)'s spacing at the torch belongs to an offset surface that folds where w exceeds a concave radius (a crater's
// floor is one), and its beads then run over each other; the torch stands along the normal at w after.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/bezier_network.h"
#include "conform/toolpath/weld/damage_map.h"
#include "conform/toolpath/intersection/surface_intersection.h"

namespace conform {

struct WeldLayerOptions {
  double bead_spacing_mm = 0.0;     // dc: distance between neighbouring beads of a layer, mm; required
  double layer_height_mm = 0.0;     // cd: height of one layer, mm; required
  double chord_error_mm = 0.0;      // delta: max chord error of a path step, mm; required, <= dc / 2
  double torch_distance_mm = 0.0;   // w: the torch's standoff along the normal, mm, <= kMaxTorchDistanceMm; the
                                    // beads are planned on the surface whatever it is (not Eq. 5's offset surface,
                                    // which folds where w exceeds a concave radius)
  double bead_width_mm = 0.0;       // width of a bead on the surface, mm, for coverage and overlap; 0: dc
  double max_overlap_mm = 2.0;      // a layer with more path length than this within half a bead of another of its
                                    // paths (beads over beads) is not ok
  int layers = 0;                   // 0: enough to fill the deepest crater, ceil((max depth - t) / cd)
  double depth_threshold_mm = -1.0; // t: < 0: 6 x the estimated noise (>= 0.01 mm); 0: any depth
  int outward_side = 0;             // 0: the damage side from the data; +1 / -1: the torch is on the side of the
                                    // reference's r_u x r_v / the other side
  BiasMode bias = BiasMode::kCheck; // a registration bias: fail (check), subtract (remove) or keep as damage
  double min_coverage_pct = 90.0;   // all the damage covered below this by layer 1: not ok (warning per crater)
  double min_crater_coverage_pct = 85.0;   // one crater (larger than a bead) covered below this: not ok
  double intersection_tolerance_mm = 0.0;  // 0: dc / 10
  double max_step_mm = 0.0;                // 0: 2 dc
  int smoothing_passes = -1;  // binomial passes over a layer's grid for its curvature (not its points); < 0: enough to
                              // smooth over dc / 4 (2 (dc / 4h)^2 for grid spacing h, at least 3, at most 50)

  bool IsValid(std::string* error) const;
};

constexpr int kMaxWeldLayers = 200;            // more is a wrong layer height (bad input, exit 2)
constexpr double kMaxTorchDistanceMm = 100.0;  // Eq. (5) for torch distances beyond this is not a weld torch
constexpr int kMaxHalfStepPaths = 20000;       // per region and layer; more: bad input (dc against the area)

struct WeldPath {
  int layer = 0;   // 1-based
  int path = 0;    // 1-based within its layer
  int region = 0;  // the damaged region (crater) it refills, 1-based
  std::vector<Eigen::Vector3d> points;   // mm, on the layer's surface ((k - 1) cd above the eroded surface)
  std::vector<Eigen::Vector3d> normals;  // outward unit normals (towards the torch)
  double bead_width_mm = 0.0;            // the bead's width on the surface (WeldLayerOptions::bead_width_mm or dc)
  int line = 0;                          // the half-step path it was cut from: pieces of one line are one bead
  double length_mm() const;
};

struct WeldLayerResult {
  bool ok = false;
  std::string termination = "not run";
  std::vector<std::string> warnings;  // what a user must know even when ok
  DamageMap damage;                   // the depth map, bias, noise, side and regions
  double noise_mm = 0.0;              // = damage.noise_mm
  double depth_threshold_mm = 0.0;    // = damage.threshold_mm
  bool threshold_estimated = false;
  double max_depth_mm = 0.0;
  std::vector<IntersectionCurve> rims;  // closed curves, then those closed along the grid's border (not `closed`)
  std::size_t border_rims = 0;          // rims closed along the border
  std::size_t open_curves = 0;          // pieces that end inside the grid (broken rims)
  std::vector<int> regions_without_rim; // region ids no rim bounds
  std::size_t box_pairs = 0;            // the intersection's work
  int layers = 0;
  std::size_t half_step_paths = 0;      // parallel paths at dc / 2 before clipping, all regions and layers
  std::vector<WeldPath> paths;          // by region, layer, then along the stepping direction
  std::vector<int> paths_per_layer;
  double total_length_mm = 0.0;
  double spacing_error_pct_max = 0.0;   // neighbouring half-step paths inside the regions vs their target g
  double chord_error_mm_max = 0.0;      // over every path step, on the surface its points lie on
  double damage_coverage_pct = 0.0;     // damaged nodes within half a bead width of a layer-1 path
  std::vector<double> crater_coverage_pct;  // per region (by id - 1): the same for its own nodes
  double bead_width_mm = 0.0;               // the bead width coverage and overlap are counted with
  std::vector<double> overlap_mm;           // per layer: its path length within half a bead of another of its lines
  double overlap_mm_max = 0.0;
  std::vector<double> coverage_pct;     // per layer: its region (remaining depth > t) within half a bead width
  double coverage_pct_min = 0.0;
  std::size_t loops_removed = 0;
  std::size_t cusps_removed = 0;
  std::size_t newton_offsets = 0;
  bool max_paths_reached = false;
  std::size_t lines_turned_back = 0;    // half-step lines dropped: the family had crossed its region and turned back
  std::size_t crossings_cut = 0;        // segments dropped where a path crossed an earlier one of its layer
  std::size_t path_crossings = 0;       // crossings left between paths of one layer and crater (not ok)
};

// Throws conform::Error when the options are not valid, a limit is hit (layers, paths, intersection work: the message
// names it) or a node lies implausibly far from the reference. ok = false (the reason in termination) when no damage
// is found, the bias is significant in check mode, the side is ambiguous, a region has no rim, a layer that should
// have paths has none, max paths are reached, the damage coverage is below min_coverage_pct, a crater's below
// min_crater_coverage_pct or a layer's overlap beyond max_overlap_mm.
WeldLayerResult plan_weld_layers(const BezierNetwork& eroded, const BezierNetwork& reference,
                                 const WeldLayerOptions& options);

}  // namespace conform
