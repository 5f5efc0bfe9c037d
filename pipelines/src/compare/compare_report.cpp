#include "conform/pipelines/compare/compare_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "conform/pipelines/common/deviation_view.h"

namespace conform {
namespace {

html::Verdict verdict_of(const CompareResult& r) {
  const DeviationStatistics& s = r.statistics;
  char text[256];
  if (s.count == 0) return {html::Level::kFail, "no scan point was matched to the reference"};
  if (!s.tolerance_mm) {
    std::snprintf(text, sizeof text, "no tolerance given: RMS %.4f mm, %zu of %zu points matched", s.rms_mm,
                  r.deviation.matched, r.scan_points);
    return {html::Level::kCheck, text};
  }
  std::snprintf(text, sizeof text, "%s: %.2f %% of the points inside +-%g mm (%.2f %% above, %.2f %% below)",
                s.within_tolerance() ? "within tolerance" : "OUT OF TOLERANCE", s.in_tolerance_pct, *s.tolerance_mm,
                s.above_pct, s.below_pct);
  return {s.within_tolerance() ? html::Level::kOk : html::Level::kFail, text};
}

}  // namespace

html::Page compare_report(const CompareOptions& options, const CompareResult& r, const nlohmann::json& json,
                          const std::string& date) {
  html::Page page;
  page.job = "compare";
  page.title = "conform compare: " + std::filesystem::path(options.scan_path).filename().string() + " against " +
               std::filesystem::path(options.reference_path).filename().string();
  page.inputs.push_back({options.scan_path, std::to_string(r.scan_points) + " points"});
  page.inputs.push_back({options.reference_path, r.reference_faces > 0
                                                     ? std::to_string(r.reference_faces) + " triangles"
                                                     : std::to_string(r.reference_points) + " points (no faces)"});
  if (!options.transform_path.empty()) page.inputs.push_back({options.transform_path, "T_ref_scan"});
  page.options = {{"units", json.value("units", "mm")},
                  {"tolerance_mm", options.tolerance_mm ? nlohmann::json(*options.tolerance_mm) : nlohmann::json()},
                  {"max_distance_mm", std::isfinite(options.max_distance_mm) ? nlohmann::json(options.max_distance_mm)
                                                                              : nlohmann::json("none")},
                  {"transform", options.transform_path.empty() ? "none" : options.transform_path}};
  page.date = date;
  page.verdict = verdict_of(r);
  page.warnings = r.warnings;
  if (!r.deviation.note.empty()) page.warnings.push_back(r.deviation.note);
  page.result = json;
  html::DeviationView view;
  html::add_deviation_view(page, r.scan_ref.vertices, r.deviation.deviation_mm, r.statistics, r.reference, view);
  html::Section& s = page.sections.back();
  s.paragraphs.insert(s.paragraphs.begin(),
                      r.deviation.is_signed()
                          ? "Signed distance of every scan point to the reference surface, + outside (the side its "
                            "normals point to)."
                          : "Unsigned distance of every scan point to the nearest reference point (the reference has "
                            "no faces).");
  return page;
}

}  // namespace conform
