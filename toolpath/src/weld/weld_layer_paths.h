#pragma once
// Private to weld_layers.cpp: the paths of one layer over one damaged region (steps 3 and 4 of weld_layers.h).

#include <vector>

#include "conform/toolpath/weld/damage_map.h"
#include "conform/toolpath/weld/weld_layers.h"

namespace conform::detail {

struct LayerPlan {
  std::vector<WeldPath> paths;            // layer, region, points, normals set; `path` numbers left to the caller
  std::vector<Eigen::Vector3d> region_nodes;  // the region's nodes deeper than the layer's level, lifted onto it
  std::size_t half_step_paths = 0;
  std::size_t loops_removed = 0, cusps_removed = 0, newton_offsets = 0;
  double chord_error_mm_max = 0.0;
  double spacing_error_pct_max = 0.0;
  bool max_paths_reached = false;
  std::size_t lines_turned_back = 0;  // half-step lines dropped after the family left the region
  std::size_t crossings_cut = 0;  // segments dropped where a path crossed an earlier one of the layer
};

// Layer k (1-based) of region `region` (its id in map.regions): empty when no node of the region is deeper than
// (k - 1) cd + t. Throws conform::Error when the paths it would need exceed kMaxHalfStepPaths.
LayerPlan plan_layer(const BezierNetwork& eroded, const DamageMap& map, int region, int k,
                     const WeldLayerOptions& options);

}  // namespace conform::detail
