#include "conform/pipelines/compare/compare_json.h"

#include "conform/pipelines/common/cad_json.h"

#include "conform/pipelines/common/json_values.h"

namespace conform {

nlohmann::json compare_json(const CompareOptions& options, const CompareResult& r, const std::string& scan_units,
                            const std::string& reference_units) {
  const DeviationStatistics& s = r.statistics;
  nlohmann::json j = {{"scan", options.scan_path},
                      {"reference", options.reference_path},
                      {"transform", json_path_or_null(options.transform_path)},
                      {"T_ref_scan", json_of(r.T_ref_scan)},
                      {"units", scan_units == reference_units ? nlohmann::json(scan_units) : nlohmann::json()},
                      {"scan_units", scan_units},
                      {"reference_units", reference_units},
                      {"signed", r.deviation.is_signed()},
                      {"note", json_path_or_null(r.deviation.note)},
                      {"points", r.scan_points},
                      {"matched", r.deviation.matched},
                      {"reference_points", r.reference_points},
                      {"reference_faces", r.reference_faces},
                      {"surface", r.reference_faces == 0 ? "points"
                                  : options.flat_facets  ? "flat facets"
                                  : r.cad_inputs.empty() ? "smooth"
                                                         : "exact CAD faces"},
                      {"exact_points", r.exact_points},
                      {"mean_mm", s.mean_mm},
                      {"std_mm", s.std_mm},
                      {"rms_mm", s.rms_mm},
                      {"min_mm", s.min_mm},
                      {"max_mm", s.max_mm},
                      {"mean_abs_mm", s.mean_abs_mm},
                      {"p5_mm", s.p5_mm},
                      {"p50_mm", s.p50_mm},
                      {"p95_mm", s.p95_mm},
                      {"p99_mm", s.p99_mm},
                      {"p95_abs_mm", s.p95_abs_mm},
                      {"percentiles", "linear between closest ranks (Hyndman & Fan 7, NumPy's default)"},
                      {"out_deviation", json_path_or_null(r.out_deviation_path)},
                      {"out_histogram", json_path_or_null(r.out_histogram_path)}};
  if (s.tolerance_mm) {
    j["tolerance_mm"] = *s.tolerance_mm;
    j["in_tolerance_pct"] = s.in_tolerance_pct;
    j["above_tolerance_pct"] = s.above_pct;
    j["below_tolerance_pct"] = s.below_pct;
    j["within_tolerance"] = s.within_tolerance();
  }
  j["cad"] = cad_json(r.cad_inputs);
  j["reference_chord_error"] = nullptr;
  if (r.reference_chord_error) {
    const ChordErrorSummary& c = *r.reference_chord_error;
    j["reference_chord_error"] = {{"max_mm", c.max_mm},
                                  {"bar_mm", c.bar_mm},
                                  {"faces_over", c.faces_over},
                                  {"area_over_mm2", c.area_over_mm2},
                                  {"area_over_pct", c.area_mm2 > 0.0 ? 100.0 * c.area_over_mm2 / c.area_mm2 : 0.0},
                                  {"too_coarse", c.faces_over > 0}};
  }
  j["warnings"] = r.warnings;
  return j;
}

}  // namespace conform
