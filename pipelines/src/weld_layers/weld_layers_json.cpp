#include "conform/pipelines/weld_layers/weld_layers_json.h"

#include <cmath>
#include <string>

#include "conform/pipelines/common/json_values.h"

namespace conform {

const char* to_string(BiasMode mode) {
  switch (mode) {
    case BiasMode::kRemove:
      return "remove";
    case BiasMode::kKeep:
      return "keep";
    case BiasMode::kCheck:
      break;
  }
  return "check";
}

nlohmann::json weld_layers_json(const WeldLayersJobOptions& options, const WeldLayersJobResult& job) {
  const WeldLayerResult& w = job.weld;
  nlohmann::json rims = nlohmann::json::array();
  for (const IntersectionCurve& c : w.rims) {
    rims.push_back({{"points", c.points.size()},
                    {"length_mm", c.length_mm()},
                    {"closed", c.closed},
                    {"closed_along_border", !c.closed}});
  }
  const DamageMap& d = w.damage;
  nlohmann::json craters = nlohmann::json::array();
  for (const DamageRegion& r : d.regions) {
    craters.push_back({{"id", r.id},
                       {"nodes", r.nodes},
                       {"area_mm2", r.area_mm2},
                       {"volume_mm3", r.volume_mm3},
                       {"max_depth_mm", r.max_depth_mm},
                       {"deepest_mm", {r.deepest.x(), r.deepest.y(), r.deepest.z()}},
                       {"deepest_row", r.deepest_row},
                       {"deepest_col", r.deepest_col},
                       {"at_border", r.at_border},
                       {"coverage_pct", static_cast<std::size_t>(r.id - 1) < w.crater_coverage_pct.size()
                                            ? nlohmann::json(w.crater_coverage_pct[static_cast<std::size_t>(r.id - 1)])
                                            : nlohmann::json(nullptr)}});
  }
  nlohmann::json bias = {{"offset_mm", d.bias_offset_mm}, {"tilt_deg", d.bias_tilt_deg},
                         {"span_mm", d.bias_span_mm},     {"significant", d.bias_significant},
                         {"removed", d.bias_removed},     {"mode", to_string(options.weld.bias)}};
  return {{"ok", w.ok},
          {"termination", w.termination},
          {"warnings", w.warnings},
          {"craters", craters},
          {"bias", bias},
          {"outward_sign", d.outward_sign},
          {"side_from_data", d.side_from_data},
          {"side_ratio", std::isfinite(d.side_ratio) ? nlohmann::json(d.side_ratio) : nlohmann::json(nullptr)},
          {"off_reference_nodes", d.off_reference},
          {"damage_coverage_pct", w.damage_coverage_pct},
          {"paths_per_layer", w.paths_per_layer},
          {"border_rims", w.border_rims},
          {"regions_without_rim", w.regions_without_rim},
          {"cusps_removed", w.cusps_removed},
          {"max_paths_reached", w.max_paths_reached},
          {"lines_turned_back", w.lines_turned_back},
          {"path_crossings", w.path_crossings},
          {"crossings_cut", w.crossings_cut},
          {"intersection_box_pairs", w.box_pairs},
          {"layers", w.layers},
          {"paths", w.paths.size()},
          {"half_step_paths", w.half_step_paths},
          {"total_length_mm", w.total_length_mm},
          {"spacing_error_pct_max", w.spacing_error_pct_max},
          {"chord_error_mm_max", w.chord_error_mm_max},
          {"coverage_pct_min", w.coverage_pct_min},
          {"coverage_pct_by_layer", w.coverage_pct},
          {"bead_width_mm", w.bead_width_mm},
          {"overlap_mm_by_layer", w.overlap_mm},
          {"overlap_mm_max", w.overlap_mm_max},
          {"max_overlap_mm", options.weld.max_overlap_mm},
          {"noise_mm", w.noise_mm},
          {"depth_threshold_mm", w.depth_threshold_mm},
          {"depth_threshold_estimated", w.threshold_estimated},
          {"max_depth_mm", w.max_depth_mm},
          {"rims", rims},
          {"open_curves", w.open_curves},
          {"loops_removed", w.loops_removed},
          {"newton_offsets", w.newton_offsets},
          {"bead_spacing_mm", options.weld.bead_spacing_mm},
          {"layer_height_mm", options.weld.layer_height_mm},
          {"chord_error_mm", options.weld.chord_error_mm},
          {"torch_distance_mm", options.weld.torch_distance_mm},
          {"reference", options.reference_path.empty() ? "coons patch of the eroded border" : options.reference_path},
          {"out", json_path_or_null(job.out_path)}};
}

}  // namespace conform
