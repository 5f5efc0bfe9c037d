#include "conform/pipelines/align/align_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "conform/core/constants.h"
#include "conform/evaluation/deviation.h"
#include "conform/evaluation/statistics.h"
#include "conform/pipelines/common/deviation_view.h"
#include "conform/report/scene.h"

namespace conform {
namespace {


html::Level level_of(AlignTrust trust) {
  switch (trust) {
    case AlignTrust::kYes:
      return html::Level::kOk;
    case AlignTrust::kCheck:
      return html::Level::kCheck;
    case AlignTrust::kNo:
      return html::Level::kFail;
  }
  return html::Level::kFail;
}

std::string share_text(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", share);
  return text;
}

html::Table fit_table(const AlignResult& r) {
  const AlignVerdict& v = r.verdict;
  html::Table t{"Fit", {"figure", "value"}, {}};
  t.rows.push_back({"trust", html::Cell(to_string(v.trust), "/trust")});
  t.rows.push_back({"ICP converged", html::Cell(r.icp.converged ? "true" : "false", "/icp_converged")});
  t.rows.push_back({"termination", html::Cell(to_string(r.icp.termination), "/termination")});
  t.rows.push_back({"iterations", html::count(static_cast<std::size_t>(r.icp.iterations), "/iterations")});
  t.rows.push_back({"method", html::Cell(to_string(r.method), "/method")});
  t.rows.push_back({"start", html::Cell(r.start, "/start")});
  // One figure per concept, named as the verdict names it: the residuals' robust std (what the verdict compares with
  // the noise) and their RMS over the pairs kept (which a few large residuals inflate) are two figures.
  t.rows.push_back({"residuals' robust std (mm)", html::number_g(v.fit_noise_mm, 4, "/verdict/fit_noise_mm")});
  t.rows.push_back({"residuals' RMS over the pairs kept (mm)", html::number(r.icp.rms_mm, 5, "/rms_mm")});
  t.rows.push_back({"inlier fraction", html::number(r.icp.inlier_fraction, 4, "/inlier_fraction")});
  t.rows.push_back({"scan noise (mm)", html::number_g(v.scan_noise_mm, 4, "/verdict/scan_noise_mm")});
  t.rows.push_back({"noise ratio", html::number(v.noise_ratio, 2, "/verdict/noise_ratio")});
  t.rows.push_back({"max distance used (mm)", html::number_g(r.max_distance_mm, 5, "/max_distance_mm")});
  t.rows.push_back({"pose std at the part (mm)", html::number_g(v.pose_std_mm, 4, "/verdict/pose_std_mm")});
  t.rows.push_back({"asked of it (mm)", html::number_g(v.pose_tolerance_mm, 4, "/verdict/pose_tolerance_mm")});
  t.rows.push_back({"scan points used", html::count(r.scan_points_used, "/scan_points_used")});
  return t;
}

html::Table pose_table(const AlignResult& r) {
  html::Table t{"T_ref_scan (maps scan coordinates into the reference frame; mm)", {}, {}};
  for (int row = 0; row < 4; ++row) {
    std::vector<html::Cell> cells;
    for (int col = 0; col < 4; ++col) {
      cells.push_back(html::number(r.icp.T_ref_scan(row, col), col == 3 ? 6 : 9,
                                   "/T_ref_scan/" + std::to_string(row) + "/" + std::to_string(col)));
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

html::Table std_table(const AlignResult& r) {
  const Vector6d& s = r.icp.degeneracy.std;
  html::Table t{"Predicted standard deviation of the pose",
                {"rx (deg)", "ry (deg)", "rz (deg)", "tx (mm)", "ty (mm)", "tz (mm)"},
                {}};
  t.rows.push_back({html::number_g(s(0) * kDegPerRad, 3, "/pose_std/rx_deg"),
                    html::number_g(s(1) * kDegPerRad, 3, "/pose_std/ry_deg"),
                    html::number_g(s(2) * kDegPerRad, 3, "/pose_std/rz_deg"), html::number_g(s(3), 3, "/pose_std/tx_mm"),
                    html::number_g(s(4), 3, "/pose_std/ty_mm"), html::number_g(s(5), 3, "/pose_std/tz_mm")});
  return t;
}

std::string vector_text(const Eigen::Vector3d& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.4f, %.4f, %.4f)", v.x(), v.y(), v.z());
  return text;
}

html::Table degenerate_table(const AlignResult& r) {
  html::Table t{"Motions the scan does not constrain (held at the start pose)", {"motion", "direction", "std"}, {}};
  for (std::size_t i = 0; i < r.icp.degeneracy.directions.size(); ++i) {
    const DegenerateDirection& d = r.icp.degeneracy.directions[i];
    const bool translation = d.kind == MotionKind::kTranslation;
    const std::string at = "/degenerate_directions/" + std::to_string(i);
    t.rows.push_back({html::Cell(translation ? "translation" : "rotation", at + "/kind"), vector_text(d.direction),
                      translation ? html::number_g(d.std_mm, 3, at + "/std_mm")
                                  : html::number_g(d.std_rad * kDegPerRad, 3, at + "/std_deg")});
  }
  return t;
}

}  // namespace

html::Page align_report(const AlignOptions& options, const AlignResult& r, const nlohmann::json& json,
                        const std::string& date) {
  html::Page page;
  page.job = "align";
  page.title = "conform align: " + std::filesystem::path(options.scan_path).filename().string() + " to " +
               std::filesystem::path(options.reference_path).filename().string();
  page.inputs.push_back({options.scan_path, std::to_string(r.scan_points) + " points"});
  page.inputs.push_back({options.reference_path, r.reference_faces > 0
                                                     ? std::to_string(r.reference_faces) + " triangles"
                                                     : std::to_string(r.reference_points) + " points (no faces)"});
  // The values the fit used: a default derived from the data shows what it came to, not the 0 that asked for it.
  const bool overlap_estimated = options.overlap == 0.0 && r.reference_faces == 0;
  page.options = {{"method", to_string(r.method)},
                  {"init", to_string(options.init)},
                  {"max_distance_mm", r.max_distance_mm},
                  {"overlap", overlap_estimated ? nlohmann::json("estimated: " + share_text(r.icp.inlier_fraction))
                                                : nlohmann::json(options.overlap > 0.0 ? options.overlap : 1.0)},
                  {"max_iterations", options.max_iterations},
                  {"free_tolerance_mm", options.free_tolerance_mm},
                  {"free_tolerance_deg", options.free_tolerance_deg},
                  {"pose_tolerance_mm", r.verdict.pose_tolerance_mm},
                  {"tolerance_mm", options.tolerance_mm},
                  {"max_noise_ratio", options.max_noise_ratio},
                  {"scan_mm_per_unit", options.scan_mm_per_unit},
                  {"reference_mm_per_unit", options.reference_mm_per_unit}};
  page.date = date;
  page.verdict = {level_of(r.verdict.trust),
                  "trust " + std::string(to_string(r.verdict.trust)) + ": " + r.verdict.summary};
  page.warnings = r.warnings;
  page.warnings.insert(page.warnings.end(), r.verdict.reasons.begin(), r.verdict.reasons.end());
  page.result = json;

  html::Section pose{"Pose", {}, {pose_table(r), std_table(r)}, {}};
  if (!r.icp.degeneracy.directions.empty()) pose.tables.push_back(degenerate_table(r));
  pose.tables.push_back(fit_table(r));
  // The scan at the pose found, its points thinned to the page's limit first (the deviations are measured for them).
  const std::size_t limit = page.scene.limits().max_points;
  const std::size_t stride = (r.scan.vertices.size() + limit - 1) / std::max<std::size_t>(limit, 1);
  std::vector<Eigen::Vector3d> shown;
  for (std::size_t i = 0; i < r.scan.vertices.size(); i += std::max<std::size_t>(stride, 1)) {
    shown.push_back(r.icp.T_ref_scan * r.scan.vertices[i]);
  }
  html::DeviationView view;
  view.tie_to_json = false;
  view.title = "Deviation of the aligned scan";
  if (!shown.empty() && !r.reference.vertices.empty()) {
    const DeviationResult d = compute_deviation(shown, r.reference);
    const DeviationStatistics s = deviation_statistics(d.deviation_mm);
    html::add_deviation_view(page, shown, d.deviation_mm, s, r.reference, view);
    page.sections.back().paragraphs.push_back(
        (d.is_signed() ? "Signed distance to the reference surface"
                       : "Unsigned distance to the nearest reference point") +
        std::string(" of the scan points shown (") + std::to_string(shown.size()) + " of " +
        std::to_string(r.scan.vertices.size()) + "), at the pose T_ref_scan above.");
  }
  page.sections.insert(page.sections.begin(), std::move(pose));
  return page;
}

}  // namespace conform
