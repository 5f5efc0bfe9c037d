#include "conform/pipelines/sicp/sicp_report.h"

#include <algorithm>

#include "conform/pipelines/sicp/sicp_json.h"

#include "common/report_pages.h"

namespace conform {
namespace {

using html::count;
using html::number;

nlohmann::json options_json(const SicpJobOptions& o) {
  const SicpCompensationOptions& c = o.compensation;
  return {{"model", to_string(c.model)},
          {"segment_length_mm", c.sicp.segmentation.segment_length_mm},
          {"overlap", c.sicp.segmentation.overlap},
          {"curvature_radius_mm", c.sicp.segmentation.curvature_radius_mm},
          {"neighbourhood_mm", c.sicp.neighbourhood_mm},
          {"stability_mm", c.sicp.stability_mm},
          {"max_distance_mm", c.sicp.max_distance_mm},
          {"scan_voxel_mm", c.sicp.scan_voxel_mm},
          {"joint_refinement", c.sicp.joint_refinement},
          {"normals", c.normals.from_scan ? "scan" : "rotate"},
          {"min_confidence", c.checks.min_confidence},
          {"max_edge_gap_mm", c.checks.max_edge_gap_mm},
          {"outlier_ratio", c.checks.outlier_ratio}};
}

html::Verdict verdict(const SicpJobResult& r) {
  const SicpCompensationResult& c = r.compensation;
  if (c.trusted) {
    return {html::Level::kOk, "trusted: every row measured, " + std::to_string(r.trajectory_rows) +
                                  " rows compensated (" + to_string(c.model) + ")"};
  }
  if (!c.converged) return {html::Level::kFail, "not converged: " + c.termination + "; no trajectory written"};
  return {html::Level::kFail, "not trusted: " + c.check.reason + "; no trajectory written"};
}

html::Table summary_table(const SicpJobResult& r) {
  const SicpCompensationResult& c = r.compensation;
  html::Table t{"Registration and checks", {"figure", "value"}, {}};
  t.rows.push_back({"contour points", count(r.contour_points, "/contour_points")});
  t.rows.push_back({"contour length (mm)", number(r.contour_length_mm, 3, "/contour_length_mm")});
  t.rows.push_back({"scan points, after thinning", count(c.registration.scan_points_used, "/scan_points_used")});
  t.rows.push_back({"rigid ICP RMS (mm)", number(c.registration.coarse.rms_mm, 4, "/rigid/rms_mm")});
  t.rows.push_back({"RMS of the model (mm)", number(sicp_json(r)["rms_mm"].get<double>(), 4, "/rms_mm")});
  t.rows.push_back({"segments", count(c.registration.segments.size())});
  t.rows.push_back({"scan noise (mm)", number(c.check.noise_mm, 4, "/checks/noise_mm")});
  t.rows.push_back({"untrusted rows", count(c.check.untrusted_rows, "/checks/untrusted_rows")});
  t.rows.push_back({"rows without edge scan", count(c.check.unmeasured_rows, "/checks/unmeasured_rows")});
  t.rows.push_back({"longest unscanned stretch (mm)", number(c.check.longest_gap_mm, 1, "/checks/longest_gap_mm")});
  t.rows.push_back({"lowest row confidence", number(c.check.min_confidence, 2, "/checks/min_confidence")});
  if (r.error) {
    const TrajectoryError& e = *r.error;
    t.rows.push_back({"off the true path, mean (mm)", number(e.path_mean_mm, 4, "/error/path_mean_mm")});
    t.rows.push_back({"off the true path, max (mm)", number(e.path_max_mm, 4, "/error/path_max_mm")});
    t.rows.push_back({"row by row vs truth, max (mm)", number(e.max_mm, 4, "/error/max_mm")});
    t.rows.push_back({"tool normals vs truth, max (deg)", number(e.normal_max_deg, 3, "/error/normal_max_deg")});
  }
  return t;
}

html::Table segments_table(const SicpJobResult& r) {
  const SicpResult& g = r.compensation.registration;
  html::Table t{"Segments",
                {"segment", "start (mm)", "length (mm)", "stability points", "ICP iterations", "RMS (mm)", "usable",
                 "confidence"},
                {}};
  for (std::size_t k = 0; k < g.segments.size(); ++k) {
    const std::string at = "/segments/" + std::to_string(k) + "/";
    const SicpSegmentFit& f = g.segments[k];
    const double confidence =
        k < r.compensation.check.segment_confidence.size() ? r.compensation.check.segment_confidence[k] : 0.0;
    t.rows.push_back({count(k, at + "index"), number(g.segmentation.segments[k].start_mm, 1, at + "start_mm"),
                      number(g.segmentation.segments[k].length_mm, 1, at + "length_mm"),
                      count(f.stability_points, at + "stability_points"),
                      count(static_cast<std::size_t>(f.icp.iterations), at + "icp_iterations"),
                      number(f.rms_mm, 4, at + "rms_mm"), f.usable ? "yes" : "no",
                      number(confidence, 2, at + "confidence")});
  }
  return t;
}

std::vector<html::Plot> plots(const SicpReportFigures& f, const SicpJobOptions& o, double noise_mm) {
  std::vector<html::Plot> out;
  html::Plot correction =
      detail::line_plot("Correction per row (compensated - nominal, in the row's frame)", "row", "correction (mm)");
  correction.series = {detail::series("across the edge", f.row, f.across_mm, html::kBlue),
                       detail::series("along the tool axis", f.row, f.axis_mm, html::kOrange),
                       detail::series("along the path", f.row, f.along_mm, html::kGreen)};
  out.push_back(correction);
  html::Plot confidence = detail::line_plot("Confidence per row", "row", "confidence");
  confidence.series = {detail::series("confidence", f.row, f.confidence, html::kPurple)};
  confidence.y_band = detail::band(0.0, o.compensation.checks.min_confidence, "untrusted below this");
  confidence.y_band->reject = true;
  out.push_back(confidence);
  if (!f.segment.empty()) {
    html::Plot residual = detail::line_plot("Residual per segment", "segment", "ICP residual RMS (mm)");
    residual.series = {detail::series("RMS", f.segment, f.segment_rms_mm, html::kBlue, true)};
    residual.y_band =
        detail::band(0.0, o.compensation.checks.outlier_ratio * noise_mm, "within the outlier ratio x the scan noise");
    out.push_back(residual);
  }
  return out;
}

void add_scene(const SicpReportFigures& f, const SicpJobResult& r, html::Scene* scene) {
  if (!r.scan.empty()) scene->add_points("scan", r.scan, html::kGrey, 1.5);
  if (!f.contour.empty()) scene->add_polyline("nominal contour", f.contour, html::kDarkGrey);
  if (!f.nominal.empty()) scene->add_polyline("nominal trajectory", f.nominal, html::kBlue);
  scene->add_polyline("compensated trajectory", f.compensated, html::kOrange);
  // Glyphs a hundredth of the contour long (10 mm on a 1 m contour), so that they read at the whole part's scale.
  const double length = std::max(1.0, r.contour_length_mm / 100.0);
  scene->add_arrows("tool normals", f.normals.origins, f.normals.directions, length, html::kGreen);
  if (!f.untrusted.empty()) scene->add_points("untrusted rows", f.untrusted, html::kRed, 6.0);
}

}  // namespace

SicpReportFigures sicp_report_figures(const SicpJobResult& r, double min_confidence) {
  SicpReportFigures f;
  f.contour = r.contour.points;
  if (r.contour.closed && !f.contour.empty()) f.contour.push_back(f.contour.front());
  f.nominal = r.nominal.points;
  const SicpCompensationResult& c = r.compensation;
  f.compensated = c.trajectory.points;
  f.normals = spread_glyphs(c.trajectory.points, c.trajectory.normals, kSicpReportGlyphs);
  const std::vector<SicpRowReport>& rows = c.check.rows;
  f.row = row_numbers(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    f.across_mm.push_back(rows[i].across_mm);
    f.axis_mm.push_back(rows[i].axis_mm);
    f.along_mm.push_back(rows[i].along_mm);
    f.confidence.push_back(rows[i].confidence);
    if (rows[i].confidence < min_confidence && i < f.compensated.size()) f.untrusted.push_back(f.compensated[i]);
  }
  const SicpResult& g = c.registration;
  for (std::size_t k = 0; k < g.segments.size(); ++k) {
    f.segment.push_back(static_cast<double>(k));
    f.segment_rms_mm.push_back(g.segments[k].rms_mm);
    f.segment_confidence.push_back(k < c.check.segment_confidence.size() ? c.check.segment_confidence[k] : 0.0);
  }
  return f;
}

html::Page sicp_report(const SicpJobOptions& options, const SicpJobResult& r) {
  html::Page page;
  page.job = "sicp";
  page.inputs = {{options.contour_path, std::to_string(r.contour_points) + " contour points, " + r.contour_source},
                 {options.scan_path, std::to_string(r.scan_points) + " points"},
                 {options.trajectory_path, std::to_string(r.trajectory_rows) + " rows"}};
  if (!options.surface_path.empty())
    page.inputs.push_back({options.surface_path, std::to_string(r.surface_faces) + " triangles"});
  if (!options.truth_path.empty()) page.inputs.push_back({options.truth_path, "ground truth"});
  page.options = options_json(options);
  page.verdict = verdict(r);
  page.warnings = r.warnings;
  page.result = sicp_json(r);
  const SicpReportFigures f = sicp_report_figures(r, options.compensation.checks.min_confidence);
  add_scene(f, r, &page.scene);
  html::Section figures{"Figures", {}, {summary_table(r)}, {}};
  if (!r.compensation.registration.segments.empty()) figures.tables.push_back(segments_table(r));
  page.sections.push_back(figures);
  page.sections.push_back({"Along the path", {}, {}, plots(f, options, r.compensation.check.noise_mm)});
  return page;
}

}  // namespace conform
