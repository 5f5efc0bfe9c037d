#include "conform/pipelines/fit_cylinder/fit_cylinder_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "conform/core/constants.h"
#include "conform/evaluation/statistics.h"
#include "conform/pipelines/common/deviation_view.h"
#include "conform/report/scene.h"

namespace conform {
namespace {

html::Table cylinder_table(const CylinderFitResult& f) {
  html::Table t{"Cylinder", {"figure", "value", "std"}, {}};
  t.rows.push_back({"radius (mm)", html::number(f.cylinder.radius_mm, 4, "/radius_mm"),
                    html::number(f.radius_std_mm, 4, "/radius_std_mm")});
  for (int k = 0; k < 3; ++k) {
    const std::string axis(1, "xyz"[k]);
    t.rows.push_back({"axis point " + axis + " (mm)",
                      html::number(f.cylinder.axis_point[k], 4, "/axis_point_mm/" + std::to_string(k)),
                      k == 0 ? html::number(f.axis_point_std_mm, 4, "/axis_point_std_mm") : html::Cell()});
  }
  for (int k = 0; k < 3; ++k) {
    const std::string axis(1, "xyz"[k]);
    t.rows.push_back({"axis direction " + axis,
                      html::number(f.cylinder.axis_direction[k], 8, "/axis_direction/" + std::to_string(k)),
                      k == 0 ? html::number(f.axis_angle_std_rad * 180.0 / kPi, 5, "/axis_angle_std_deg")
                             : html::Cell()});
  }
  return t;
}

html::Table fit_table(const FitCylinderJobResult& job) {
  const CylinderFitResult& f = job.fit;
  html::Table t{"Fit", {"figure", "value"}, {}};
  t.rows.push_back({"ok", html::Cell(f.ok ? "true" : "false", "/ok")});
  t.rows.push_back({"termination", html::Cell(f.termination, "/termination")});
  t.rows.push_back({"points", html::count(job.points, "/points")});
  t.rows.push_back({"inliers", html::count(f.inliers.size(), "/inliers")});
  t.rows.push_back({"inlier fraction", html::number(f.inlier_fraction, 4, "/inlier_fraction")});
  t.rows.push_back({"inlier threshold (mm)", html::number(f.threshold_mm, 4, "/threshold_mm")});
  t.rows.push_back({"RMS (mm)", html::number(f.rms_mm, 4, "/rms_mm")});
  t.rows.push_back({"noise sigma (mm)", html::number(f.noise_sigma_mm, 4, "/noise_sigma_mm")});
  t.rows.push_back({"arc (deg)", html::number(f.arc_rad * 180.0 / kPi, 2, "/arc_deg")});
  t.rows.push_back({"surface side", html::Cell(to_string(f.side), "/side")});
  t.rows.push_back({"normals", html::Cell(to_string(job.normals), "/normals")});
  t.rows.push_back({"RANSAC draws", html::count(static_cast<std::size_t>(f.ransac_iterations), "/ransac_iterations")});
  return t;
}

}  // namespace

Mesh cylinder_mesh(const Cylinder& c, double t0, double t1, int segments, int rings) {
  const Eigen::Vector3d a = c.axis_direction.normalized();
  const Eigen::Vector3d u = a.unitOrthogonal(), v = a.cross(u);
  Mesh m;
  for (int i = 0; i <= rings; ++i) {
    const double t = t0 + (t1 - t0) * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * kPi * j / segments;
      const Eigen::Vector3d radial = std::cos(phi) * u + std::sin(phi) * v;
      m.vertices.push_back(c.axis_point + t * a + c.radius_mm * radial);
      m.normals.push_back(radial);
    }
  }
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const int p = i * segments + j, q = i * segments + (j + 1) % segments;
      m.faces.push_back({p, q, q + segments});
      m.faces.push_back({p, q + segments, p + segments});
    }
  }
  return m;
}

html::Page fit_cylinder_report(const FitCylinderJobOptions& options, const FitCylinderJobResult& job,
                               const nlohmann::json& json, const std::string& date) {
  const CylinderFitResult& f = job.fit;
  html::Page page;
  page.job = "fit-cylinder";
  page.title = "conform fit-cylinder: " + std::filesystem::path(options.input_path).filename().string();
  page.inputs.push_back({options.input_path, std::to_string(job.points) + " points"});
  page.options = {{"threshold_mm", options.fit.threshold_mm}, {"min_radius_mm", options.fit.min_radius_mm},
                  {"normals_k", options.fit.normal_neighbors}, {"seed", options.fit.seed}};
  page.date = date;
  char text[200];
  std::snprintf(text, sizeof text, "cylinder: radius %.4f mm, %.2f %% inliers, RMS %.4f mm", f.cylinder.radius_mm,
                100.0 * f.inlier_fraction, f.rms_mm);
  page.verdict = f.ok ? html::Verdict{html::Level::kOk, text} : html::Verdict{html::Level::kFail, "no cylinder: " + f.termination};
  page.warnings = job.warnings;
  page.result = json;
  html::Section figures{"Fit", {}, {}, {}};
  if (f.refine_rounds == 0 || job.points_mm.empty()) {  // RANSAC found no model: the points only
    page.scene.add_points("points", job.points_mm, html::kGrey, 2.0);
    figures.tables.push_back(fit_table(job));
    page.sections.push_back(std::move(figures));
    return page;
  }
  std::vector<double> residual_mm;
  double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
  const Eigen::Vector3d a = f.cylinder.axis_direction.normalized();
  for (const Eigen::Vector3d& p : job.points_mm) {
    residual_mm.push_back(signed_distance(f.cylinder, p));
    const double t = (p - f.cylinder.axis_point).dot(a);
    t0 = std::min(t0, t), t1 = std::max(t1, t);
  }
  DeviationStatisticsOptions band;
  if (f.threshold_mm > 0.0) band.tolerance_mm = f.threshold_mm;
  const DeviationStatistics s = deviation_statistics(residual_mm, band);
  html::DeviationView view;
  view.scan_name = "points";
  view.reference_name = "fitted cylinder";
  view.tie_to_json = false;
  view.quantity = "residual";
  view.title = "Residuals (signed distance to the cylinder, + away from the axis; band: the inlier threshold)";
  html::add_deviation_view(page, job.points_mm, residual_mm, s, cylinder_mesh(f.cylinder, t0, t1), view);
  const double margin = 0.1 * (t1 - t0);
  page.scene.add_polyline("axis", {f.cylinder.axis_point + (t0 - margin) * a, f.cylinder.axis_point + (t1 + margin) * a},
                          html::kPurple);
  figures.tables = {cylinder_table(f), fit_table(job)};
  page.sections.insert(page.sections.begin(), std::move(figures));
  return page;
}

}  // namespace conform
