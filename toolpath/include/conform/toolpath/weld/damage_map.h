#pragma once
// Where an eroded grid lies below its reference, and how sure we are (the first step of `conform weld-layers`; the
// paper, Simas/Dias/Guenther section 2, takes the damaged area as given by the intersection):
//   1. the signed distance d of every eroded grid node from the reference along its normal r_u x r_v (closest point by
//      Newton from the nearest reference node, a kd-tree: O(n log n));
//   2. registration bias: a plane d = a + b.(p - c) fitted to d by least squares on the undamaged surface only: the
//      nodes within 3 noise sigmas of the most common level (a band shrunk onto the mode of the residuals) and at
//      least bias_margin_mm away from every feature. Craters, lips and bumps do not pull it, however much of the grid
//      they cover, as long as the undamaged surface is the most common level. Its offset and tilt are reported;
//      BiasMode says whether a significant one fails the job, is subtracted from d or kept;
//   3. noise: 1.4826 x the median absolute local residual of d (d minus the mean of its 4 neighbours, divided by
//      sqrt(5/4) for white noise). A smooth lip, bump or crater barely changes a local residual and the median ignores
//      the few it does: features cannot inflate the estimate;
//   4. which side is damage: the side of the reference with the larger volume beyond the threshold (sum of
//      |d| - t over the nodes past it), ambiguous when the two are within a factor side_ratio_min;
//   5. depth = d towards that side; the damaged regions are the nodes deeper than the threshold t (default
//      noise_factor x noise, at least min_threshold_mm), grouped by hysteresis: two such nodes are one region when
//      a chain of 8-connected nodes deeper than t / 2 joins them (a crater's fringe broken up by noise stays one
//      crater).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/bezier_network.h"

namespace conform {

// What to do with a registration bias (offset or tilt of the eroded grid against the reference).
enum class BiasMode {
  kCheck,   // a significant bias is a failure of the job (the result says so): register the grids first
  kRemove,  // subtract the fitted plane from the depths
  kKeep,    // keep it as damage (uniform wear): reported, not removed
};

struct DamageOptions {
  double depth_threshold_mm = -1.0;  // t: < 0: noise_factor x noise (>= min_threshold_mm); 0: any depth
  double noise_factor = 6.0;         // clear of the noise's tails (6 sigma: 1e-9 false nodes)
  double min_threshold_mm = 0.01;    // floor of the estimated threshold (noise-free data)
  int outward_side = 0;              // 0: from the data; +1: the torch (outside) is on the side of the reference's
                                     // r_u x r_v; -1: on the other side
  BiasMode bias = BiasMode::kCheck;
  double bias_tolerance_mm = 0.05;   // a bias plane that moves no node by more than this (or 3 noise) is not reported
  double bias_margin_mm = 2.0;       // the bias plane is fitted this far from every feature (crater, lip, bump)
  double side_ratio_min = 2.0;       // volumes of the two sides closer than this: ambiguous
  double max_deviation_mm = 100.0;   // a node farther than this from the reference: bad input (the grids differ)

  bool IsValid(std::string* error) const;
};

struct DamageRegion {
  int id = 0;                    // 1-based, by decreasing volume
  std::size_t nodes = 0;         // grid nodes deeper than the threshold
  double area_mm2 = 0.0;
  double volume_mm3 = 0.0;       // sum of (depth - t) x node area
  double max_depth_mm = 0.0;
  Eigen::Vector3d deepest = Eigen::Vector3d::Zero();  // the deepest node, mm
  int deepest_row = 0, deepest_col = 0;
  bool at_border = false;        // has a node on the grid's border
  int row_min = 0, row_max = 0, col_min = 0, col_max = 0;  // its nodes' box on the grid
};

struct DamageMap {
  int rows = 0, cols = 0;
  std::vector<double> depth;              // per eroded node (row-major), mm, positive below the reference; the bias
                                          // removed when asked; 0 where the node has no reference under it
  std::vector<Eigen::Vector3d> outward;   // per node: the reference's unit normal towards the torch
  std::vector<int> label;                 // per node: its region's id, 0 for none
  std::vector<DamageRegion> regions;
  double noise_mm = 0.0;
  double threshold_mm = 0.0;
  bool threshold_estimated = false;
  double max_depth_mm = 0.0;
  double bias_offset_mm = 0.0;   // the plane's value at the grid's centre, along the torch side (+: eroded above)
  double bias_tilt_deg = 0.0;    // the plane's slope
  double bias_span_mm = 0.0;     // the most it moves a node
  bool bias_significant = false; // span above max(bias_tolerance_mm, 3 noise)
  bool bias_removed = false;
  int outward_sign = 1;          // the torch is on the side of sign x r_u x r_v of the reference
  bool side_from_data = true;
  bool side_ambiguous = false;
  double side_ratio = 0.0;       // volume on the damage side / volume on the other (inf when none there)
  std::size_t off_reference = 0; // nodes whose closest reference point is on the reference's border, beyond it
  // The fitted bias plane, along the reference's r_u x r_v: bias_a + bias_b . ((p - bias_centre) . (e1, e2)).
  double bias_a = 0.0;
  Eigen::Vector2d bias_b = Eigen::Vector2d::Zero();
  Eigen::Vector3d bias_centre = Eigen::Vector3d::Zero(), bias_e1 = Eigen::Vector3d::UnitX(),
                  bias_e2 = Eigen::Vector3d::UnitY();
  double bias_at(const Eigen::Vector3d& p) const {
    return bias_a + bias_b.x() * (p - bias_centre).dot(bias_e1) + bias_b.y() * (p - bias_centre).dot(bias_e2);
  }

  double at(int r, int c) const { return depth[static_cast<std::size_t>(r * cols + c)]; }
};

// Throws conform::Error when the options are not valid or a node is farther than max_deviation_mm from the reference
// (naming the node).
DamageMap map_damage(const BezierNetwork& eroded, const BezierNetwork& reference, const DamageOptions& options);

// % of the damage (nodes deeper than the map's threshold) within `radius_mm` of one of the polylines (their points
// in mm, densified); 100 when there is no damage.
double damage_coverage_pct(const BezierNetwork& eroded, const DamageMap& map,
                           const std::vector<std::vector<Eigen::Vector3d>>& polylines, double radius_mm);

// Robust helpers: the median, and 1.4826 x the median absolute deviation from the median (sigma for normal data).
double median_of(std::vector<double> values);
double robust_sigma(const std::vector<double>& values);

}  // namespace conform
