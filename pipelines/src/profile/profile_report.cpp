#include "conform/pipelines/profile/profile_report.h"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "conform/pipelines/profile/profile_json.h"

#include "common/report_pages.h"

namespace conform {
namespace {

ProfileStraightFrame straight_frame(const ProfileCompensationResult& r) {
  const ProfileEdgeCurve& c = r.edge.curve;
  ProfileStraightFrame f;
  f.origin = c.position(c.t_begin());
  const Eigen::Vector3d chord = c.position(c.t_end()) - f.origin;
  if (chord.norm() > 0.0) f.along = chord.normalized();
  const Eigen::Vector3d z = r.local_web ? Eigen::Vector3d::UnitZ() : r.web_normal;
  const Eigen::Vector3d across = z.cross(f.along);  // Eq. (5), on the straight profile
  if (across.norm() > 0.0) f.across = across.normalized();
  return f;
}

std::vector<Eigen::Vector3d> edge_curve(const ProfileEdgeCurve& c) {
  std::vector<Eigen::Vector3d> out;
  const double length = c.length_mm();
  if (!(length > 0.0)) return out;
  const std::size_t n = kProfileReportCurvePoints;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = length * static_cast<double>(i) / static_cast<double>(n - 1);
    out.push_back(c.position(c.approximate_parameter_at(s)));
  }
  return out;
}

ProfileFeatureFigure feature_figure(const ProfileFeatureResult& r, const ProfileStraightFrame& frame) {
  ProfileFeatureFigure f;
  f.id = r.id;
  f.type = to_string(r.type);
  f.mapped = r.mapped;
  for (std::size_t i = 0; i < r.designed.size() && i < r.mapped.size(); ++i) {
    f.nominal.push_back(frame.at(r.designed[i]));
    f.max_displacement_mm = std::max(f.max_displacement_mm, (r.mapped[i] - f.nominal.back()).norm());
  }
  if (r.has_centre) {
    f.designed = r.designed_centre;
    f.mapped_at = r.centre;
  } else if (!r.designed.empty() && !r.mapped.empty()) {
    f.designed = r.designed.front();
    f.mapped_at = r.mapped.front();
  }
  f.nominal_at = frame.at(f.designed);
  f.displacement_mm = (f.mapped_at - f.nominal_at).norm();
  f.max_displacement_mm = std::max(f.max_displacement_mm, f.displacement_mm);
  return f;
}

using html::count;
using html::number;

nlohmann::json options_json(const ProfileJobOptions& o) {
  const ProfileCompensationOptions& c = o.compensation;
  return {{"model", to_string(c.edge.model)},
          {"web", !o.second_edge_path.empty() ? "second edge"
                  : c.fit_web_plane           ? "fitted plane"
                  : c.web_normal              ? "given"
                                              : "machine +z"},
          {"web_width_mm", c.web_width_mm},
          {"direction", c.reversed ? "reverse" : "forward"},
          {"knot_spacing_mm", c.edge.knot_spacing_mm},
          {"outlier_sigma", c.edge.outlier_threshold_sigma},
          {"chord_tolerance_mm", c.sampling.chord_tolerance_mm},
          {"max_gap_mm", c.edge.points.max_gap_mm},
          {"noise_mm", c.edge.noise_mm}};
}

html::Table edge_table(const ProfileJobResult& job) {
  const ProfileCompensationResult& r = job.compensation;
  html::Table t{"Edge", {"figure", "value"}, {}};
  t.rows.push_back({"edge points", count(job.edge_points, "/edge_points")});
  t.rows.push_back({"edge length (mm)", number(r.edge.curve.length_mm(), 3, "/edge_length_mm")});
  t.rows.push_back({"median spacing (mm)", number(r.edge.points.median_spacing_mm, 3, "/edge_spacing_median_mm")});
  t.rows.push_back({"largest gap (mm)", number(r.edge.points.max_gap_mm, 3, "/edge_gap_max_mm")});
  t.rows.push_back({"noise (mm)", number(r.edge.noise_mm, 4, "/noise_mm")});
  t.rows.push_back({"outliers rejected", count(r.edge.outliers, "/edge_outliers")});
  t.rows.push_back({"model", {to_string(r.edge.model), "/model"}});
  t.rows.push_back({"fit RMS (mm)", number(r.edge.rms_mm, 4, "/edge_rms_mm")});
  t.rows.push_back({"fit max (mm)", number(r.edge.max_mm, 4, "/edge_max_mm")});
  t.rows.push_back({"web", {r.web_source, "/web"}});
  t.rows.push_back({"mapped points", count(r.mapped_points, "/mapped_points")});
  t.rows.push_back(
      {"arc-length residual max (mm)", html::number_g(r.arc_length_residual_max_mm, 3, "/arc_length_residual_max_mm")});
  return t;
}

std::string xyz(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "%.3f, %.3f, %.3f", p.x(), p.y(), p.z());
  return text;
}

html::Table feature_table(const ProfileReportFigures& f, const ProfileJobResult& job) {
  html::Table t{"Features: nominal (straight profile) and mapped (deformed profile)",
                {"id", "type", "points", "Tx (mm)", "Ty (mm)", "mapped x, y, z (mm)", "displacement (mm)",
                 "max displacement (mm)", "vs cubic (mm)"},
                {}};
  for (std::size_t k = 0; k < f.features.size(); ++k) {
    const ProfileFeatureFigure& g = f.features[k];
    const std::string at = "/features/" + std::to_string(k) + "/";
    t.rows.push_back({{g.id, at + "id"},
                      {g.type, at + "type"},
                      count(g.mapped.size(), at + "points"),
                      number(g.designed.x(), 3),
                      number(g.designed.y(), 3),
                      xyz(g.mapped_at),
                      number(g.displacement_mm, 3),
                      number(g.max_displacement_mm, 3),
                      number(job.compensation.features[k].cubic_deviation_max_mm, 3, at + "cubic_deviation_max_mm")});
  }
  return t;
}

html::Plot displacement_plot(const ProfileReportFigures& f) {
  html::Plot p = detail::line_plot("Feature displacement along the profile", "Ty (mm)", "|mapped - nominal| (mm)");
  html::Series s = detail::series("displacement", {}, {}, html::kOrange, true);
  std::vector<std::pair<double, double>> points;
  for (const ProfileFeatureFigure& g : f.features) points.emplace_back(g.designed.y(), g.displacement_mm);
  std::sort(points.begin(), points.end());
  for (const auto& [ty, d] : points) s.x.push_back(ty), s.y.push_back(d);
  p.series.push_back(s);
  return p;
}

// The part seen from above in the straight profile's frame (along the chord, across it), the across axis stretched
// to the plot's height: a profile metres long and a few hundred millimetres wide is a line at true scale in 3D.
html::Plot plan_plot(const ProfileReportFigures& f) {
  html::Plot p = detail::line_plot("Plan view along the chord (across stretched to fit; nominal blue, mapped orange)",
                                   "along the chord, from the edge's start (mm)", "across (mm)");
  const ProfileStraightFrame& frame = f.straight;
  const auto add = [&frame](html::Series* s, const Eigen::Vector3d& q) {
    s->x.push_back((q - frame.origin).dot(frame.along));
    s->y.push_back((q - frame.origin).dot(frame.across));
  };
  const auto gap = [](html::Series* s) {
    s->x.push_back(std::numeric_limits<double>::quiet_NaN());
    s->y.push_back(std::numeric_limits<double>::quiet_NaN());
  };
  html::Series edge = detail::series("edge curve", {}, {}, html::kDarkGrey);
  for (const Eigen::Vector3d& q : f.edge_curve) add(&edge, q);
  html::Series straight = detail::series("straight edge (nominal)", {}, {}, html::kGrey);
  if (!f.edge_curve.empty()) add(&straight, f.edge_curve.front()), add(&straight, f.edge_curve.back());
  html::Series nominal = detail::series("features, nominal", {}, {}, html::kBlue);
  html::Series mapped = detail::series("features, mapped", {}, {}, html::kOrange);
  html::Series nominal_marks = detail::series("", {}, {}, html::kBlue, true);
  html::Series mapped_marks = detail::series("", {}, {}, html::kOrange, true);
  for (const ProfileFeatureFigure& g : f.features) {
    for (const Eigen::Vector3d& q : g.nominal) add(&nominal, q);
    for (const Eigen::Vector3d& q : g.mapped) add(&mapped, q);
    gap(&nominal), gap(&mapped);
    // A dot at each feature's reference point, so that a feature narrower than a pixel still shows.
    add(&nominal_marks, g.nominal_at), gap(&nominal_marks);
    add(&mapped_marks, g.mapped_at), gap(&mapped_marks);
  }
  p.series = {straight, edge, nominal, mapped, nominal_marks, mapped_marks};
  return p;
}

void add_scene(const ProfileReportFigures& f, html::Scene* scene) {
  if (!f.edge.empty()) scene->add_points("edge points", f.edge, html::kGrey, 3.0);
  if (!f.second_edge.empty()) scene->add_points("second edge points", f.second_edge, html::kGrey, 3.0);
  scene->add_polyline("edge curve", f.edge_curve, html::kDarkGrey);
  std::vector<std::vector<Eigen::Vector3d>> nominal, mapped;
  std::vector<Eigen::Vector3d> nominal_points, mapped_points;  // features of one point (a mark)
  for (const ProfileFeatureFigure& g : f.features) {
    if (g.nominal.size() > 1) nominal.push_back(g.nominal), mapped.push_back(g.mapped);
    if (g.nominal.size() == 1) nominal_points.push_back(g.nominal[0]), mapped_points.push_back(g.mapped[0]);
  }
  scene->add_polylines("features, nominal (straight profile)", nominal, html::kBlue);
  scene->add_polylines("features, mapped (deformed profile)", mapped, html::kOrange);
  if (!nominal_points.empty()) {
    scene->add_points("point features, nominal", nominal_points, html::kBlue, 6.0);
    scene->add_points("point features, mapped", mapped_points, html::kOrange, 6.0);
  }
}

}  // namespace

ProfileReportFigures profile_report_figures(const ProfileJobResult& job) {
  const ProfileCompensationResult& r = job.compensation;
  ProfileReportFigures f;
  f.edge = job.edge;
  f.second_edge = job.second_edge;
  f.edge_curve = edge_curve(r.edge.curve);
  f.straight = straight_frame(r);
  for (const ProfileFeatureResult& feature : r.features) f.features.push_back(feature_figure(feature, f.straight));
  return f;
}

html::Page profile_report(const ProfileJobOptions& options, const ProfileJobResult& job) {
  const ProfileCompensationResult& r = job.compensation;
  html::Page page;
  page.job = "profile";
  page.inputs = {{options.edge_path, std::to_string(job.edge_points) + " edge points"},
                 {options.features_path, std::to_string(r.features.size()) + " features"}};
  if (!options.second_edge_path.empty())
    page.inputs.push_back({options.second_edge_path, std::to_string(job.second_edge_points) + " edge points"});
  page.options = options_json(options);
  page.verdict = r.ok ? html::Verdict{html::Level::kOk, std::to_string(r.features.size()) + " features mapped, " +
                                                            std::to_string(job.out_rows) + " rows"}
                      : html::Verdict{html::Level::kFail, r.termination + "; no file written"};
  if (r.ok && !r.warnings.empty()) page.verdict.level = html::Level::kCheck;
  page.warnings = r.warnings;
  page.result = profile_json(options, job);
  const ProfileReportFigures f = profile_report_figures(job);
  add_scene(f, &page.scene);
  page.sections.push_back({"Plan view", {}, {}, {plan_plot(f)}});
  page.sections.push_back({"Figures",
                           {"Nominal: a feature on the straight profile laid from the edge's origin along its "
                            "chord; displacement: how far the deformation moves it (centre, or first point)."},
                           {edge_table(job), feature_table(f, job)},
                           {displacement_plot(f)}});
  return page;
}

}  // namespace conform
