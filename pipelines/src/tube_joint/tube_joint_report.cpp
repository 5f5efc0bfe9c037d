#include "conform/pipelines/tube_joint/tube_joint_report.h"

#include <cmath>

#include "conform/core/constants.h"
#include "conform/pipelines/tube_joint/tube_joint_json.h"

#include "common/report_pages.h"

namespace conform {
namespace {

using html::count;
using html::number;


// An option given in degrees, back from radians for the page: 30, not 29.999999999999996.
double option_deg(double rad) { return std::round(rad * kDegPerRad * 1e9) / 1e9; }

ReportGlyphs tool_glyphs(const std::vector<ToolPose>& poses) {
  std::vector<Eigen::Vector3d> at, direction;
  for (const ToolPose& p : poses) at.push_back(p.position), direction.push_back(p.direction);
  return spread_glyphs(at, direction, kTubeJointReportGlyphs);
}

nlohmann::json options_json(const TubeJointJobOptions& o) {
  nlohmann::json j = {{"cut_standoff_mm", o.solve.tools.cut_standoff_mm},
                      {"weld_standoff_mm", o.solve.tools.weld_standoff_mm},
                      {"weld_angle_deg", option_deg(o.solve.tools.weld_angle_rad)},
                      {"k_normals", o.solve.geometry.k_normals},
                      {"k_refine", o.solve.geometry.k_refine},
                      {"max_facet_error_mm", o.solve.max_facet_error_mm},
                      {"island_ratio", o.solve.max_island_ratio}};
  if (o.leg_pose_path.empty()) {
    j["pitch_deg"] = option_deg(o.spec.pitch_rad);
    j["offset_mm"] = o.spec.offset_mm;
    j["protrusion_mm"] = o.spec.protrusion_mm;
  } else {
    j["leg_pose"] = o.leg_pose_path;
  }
  if (o.solve.tools.groove_table_rad.empty()) {
    nlohmann::json groove = nlohmann::json::array();
    for (const double a : o.solve.tools.groove_rad) groove.push_back(option_deg(a));
    j["groove_deg"] = groove;
  }
  if (o.solve.sampling.spacing == PathSpacing::kArcLength) {
    j["step_mm"] = o.solve.sampling.step_mm;
  } else {
    j["step_deg"] = option_deg(o.solve.sampling.step_rad);
  }
  return j;
}

html::Verdict verdict(const TubeJointSolution& s) {
  if (s.ok) {
    return {s.safety.walls_checked ? html::Level::kOk : html::Level::kCheck,
            "one closed seam, " + std::to_string(s.path.points.size()) + " points; tools " +
                (s.safety.walls_checked ? "clear of the walls" : "not checked against the walls (no wall thickness)")};
  }
  return {html::Level::kFail, "[" + s.check.condition + "] " + s.termination + "; no file written"};
}

html::Table figures_table(const TubeJointJobResult& job) {
  const TubeJointSolution& s = job.solution;
  html::Table t{"Intersection and path", {"figure", "value"}, {}};
  t.rows.push_back({"leg triangles", count(job.leg_faces, "/leg_faces")});
  t.rows.push_back({"stub triangles", count(job.stub_faces, "/stub_faces")});
  t.rows.push_back({"intersection segments", count(s.segments, "/segments")});
  t.rows.push_back({"curve vertices", count(s.curve_vertices, "/curve_vertices")});
  t.rows.push_back({"islands dropped", count(s.islands, "/islands")});
  t.rows.push_back({"vertices dropped as backtracking", count(s.dropped_vertices, "/dropped_vertices")});
  t.rows.push_back({"leg scan noise (mm)", number(s.leg_quality.noise_mm, 3, "/leg_scan/noise_mm")});
  t.rows.push_back({"stub scan noise (mm)", number(s.stub_quality.noise_mm, 3, "/stub_scan/noise_mm")});
  t.rows.push_back({"smallest crossing angle (deg)", number(s.min_crossing_deg, 2, "/min_crossing_deg")});
  t.rows.push_back({"facet error bound (mm)", number(s.facet_error_mm, 3, "/facet_error_mm")});
  if (s.ok) {
    t.rows.push_back({"path points", count(s.path.points.size(), "/points")});
    t.rows.push_back({"path length (mm)", number(s.path.length_mm, 3, "/path_length_mm")});
    t.rows.push_back({"step min (mm)", number(s.path.min_step_mm, 3, "/min_step_mm")});
    t.rows.push_back({"step max (mm)", number(s.path.max_step_mm, 3, "/max_step_mm")});
    t.rows.push_back({"points refined onto both scans", count(s.refined_points, "/refined_points")});
  }
  return t;
}

html::Plot angle_plot(const TubeJointReportFigures& f) {
  html::Plot p = detail::line_plot("Angles along the seam", "stub azimuth phi (deg), from the toe", "angle (deg)");
  p.series = {detail::series("dihedral psi", f.azimuth_deg, f.dihedral_deg, html::kBlue),
              detail::series("groove (bevel) alpha_c", f.azimuth_deg, f.groove_deg, html::kOrange),
              detail::series("weld torch alpha_w", f.azimuth_deg, f.weld_deg, html::kGreen)};
  p.x_marks = {90.0, 180.0, 270.0};
  return p;
}

void add_scene(const TubeJointReportFigures& f, const TubeJointJobResult& job, html::Scene* scene) {
  if (!f.leg_S.faces.empty()) scene->add_mesh("leg (outer surface)", f.leg_S, html::kGrey, 0.6);
  if (!job.stub_S.faces.empty()) scene->add_mesh("stub (inner surface)", job.stub_S, html::kBlue, 0.4);
  if (!f.path.empty()) scene->add_polyline("seam path", f.path, html::kRed);
  if (!f.cut.origins.empty()) {
    scene->add_arrows("cutting tool", f.cut.origins, f.cut.directions, f.cut_standoff_mm, html::kOrange);
    scene->add_arrows("welding torch", f.weld.origins, f.weld.directions, f.weld_standoff_mm, html::kGreen);
  }
  if (!job.solution.ok && job.solution.segments > 0) {
    scene->add_points("where it failed", {job.solution.check.where}, html::kRed, 12.0);
  }
}

}  // namespace

TubeJointReportFigures tube_joint_report_figures(const TubeJointJobResult& job, double cut_standoff_mm,
                                                 double weld_standoff_mm) {
  TubeJointReportFigures f;
  f.leg_S = job.leg_L;
  for (Eigen::Vector3d& v : f.leg_S.vertices) v = job.T_S_L * v;
  for (Eigen::Vector3d& n : f.leg_S.normals) n = job.T_S_L.linear() * n;
  f.cut_standoff_mm = cut_standoff_mm;
  f.weld_standoff_mm = weld_standoff_mm;
  const TubeJointSolution& s = job.solution;
  if (!s.ok) return f;
  for (const PathFrame& frame : s.frames) f.path.push_back(frame.point);
  if (!f.path.empty()) f.path.push_back(f.path.front());
  f.cut = tool_glyphs(s.tools.cut);
  f.weld = tool_glyphs(s.tools.weld);
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    f.azimuth_deg.push_back(s.frames[i].phi_rad * kDegPerRad);
    f.dihedral_deg.push_back(i < s.tools.psi_rad.size() ? s.tools.psi_rad[i] * kDegPerRad : 0.0);
    f.groove_deg.push_back(i < s.tools.groove_rad.size() ? s.tools.groove_rad[i] * kDegPerRad : 0.0);
    f.weld_deg.push_back(s.tools.weld_angle_rad * kDegPerRad);
  }
  return f;
}

html::Page tube_joint_report(const TubeJointJobOptions& options, const TubeJointJobResult& job) {
  html::Page page;
  page.job = "tube-joint";
  page.inputs = {{options.leg_path, std::to_string(job.leg_faces) + " triangles"},
                 {options.stub_path, std::to_string(job.stub_faces) + " triangles"}};
  for (const std::string* path : {&options.leg_pose_path, &options.leg_markers_path, &options.stub_markers_path}) {
    if (!path->empty()) page.inputs.push_back({*path, ""});
  }
  page.options = options_json(options);
  page.verdict = verdict(job.solution);
  page.warnings = job.solution.warnings;
  page.result = tube_joint_json(job);
  const TubeJointReportFigures f =
      tube_joint_report_figures(job, options.solve.tools.cut_standoff_mm, options.solve.tools.weld_standoff_mm);
  add_scene(f, job, &page.scene);
  html::Section figures{"Figures",
                        {"Stub frame S: z along the stub axis towards the leg, x towards the toe. Tool glyphs run "
                         "from the tool's position to the seam (the standoff)."},
                        {figures_table(job)},
                        {}};
  if (!f.azimuth_deg.empty()) figures.plots.push_back(angle_plot(f));
  page.sections.push_back(figures);
  return page;
}

}  // namespace conform
