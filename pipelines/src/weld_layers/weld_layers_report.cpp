#include "conform/pipelines/weld_layers/weld_layers_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "conform/pipelines/weld_layers/weld_layers_json.h"

#include "common/report_pages.h"

namespace conform {
namespace {

// Grid rows and columns kept: every stride-th, and the last.
std::vector<int> kept(int n, int stride) {
  std::vector<int> out;
  for (int i = 0; i < n; i += stride) out.push_back(i);
  if (out.back() != n - 1) out.push_back(n - 1);
  return out;
}

void add_surface(const WeldLayersJobResult& job, std::size_t max_nodes, WeldLayersReportFigures* f) {
  const SurfaceGrid& g = job.eroded;
  if (g.rows < 2 || g.cols < 2) return;
  const double nodes = static_cast<double>(g.rows) * static_cast<double>(g.cols);
  const double limit = static_cast<double>(std::max<std::size_t>(1, max_nodes));
  f->stride = std::max(1, static_cast<int>(std::ceil(std::sqrt(nodes / limit))));
  const std::vector<int> rows = kept(g.rows, f->stride);
  const std::vector<int> cols = kept(g.cols, f->stride);
  const DamageMap& d = job.weld.damage;
  const bool has_depth = d.rows == g.rows && d.cols == g.cols && !d.depth.empty();
  for (const int r : rows) {
    for (const int c : cols) {
      f->surface.vertices.push_back(g.at(r, c));
      f->depth_mm.push_back(has_depth ? d.at(r, c) : 0.0);
    }
  }
  const auto index = [&](std::size_t r, std::size_t c) { return static_cast<int>(r * cols.size() + c); };
  for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
    for (std::size_t c = 0; c + 1 < cols.size(); ++c) {
      f->surface.faces.push_back({index(r, c), index(r, c + 1), index(r + 1, c + 1)});
      f->surface.faces.push_back({index(r, c), index(r + 1, c + 1), index(r + 1, c)});
    }
  }
}

using html::count;
using html::number;

// Distinct colours for layers 1, 2, ... (cycled).
const html::Rgb kLayerColours[] = {html::kBlue,   html::kOrange, html::kGreen,
                                   html::kPurple, html::kRed,    html::kDarkGrey};

nlohmann::json options_json(const WeldLayersJobOptions& o) {
  return {{"bead_spacing_mm", o.weld.bead_spacing_mm},
          {"layer_height_mm", o.weld.layer_height_mm},
          {"chord_error_mm", o.weld.chord_error_mm},
          {"torch_distance_mm", o.weld.torch_distance_mm},
          {"layers", o.weld.layers},
          {"depth_threshold_mm", o.weld.depth_threshold_mm},
          {"outward", o.weld.outward_side},
          {"bias", to_string(o.weld.bias)},
          {"min_coverage_pct", o.weld.min_coverage_pct},
          {"min_crater_coverage_pct", o.weld.min_crater_coverage_pct},
          {"reference", o.reference_path.empty() ? "coons patch of the eroded border" : o.reference_path}};
}

html::Table damage_table(const WeldLayerResult& w) {
  html::Table t{"Damage", {"figure", "value"}, {}};
  t.rows.push_back({"noise (mm)", number(w.noise_mm, 4, "/noise_mm")});
  t.rows.push_back({"depth threshold (mm)", number(w.depth_threshold_mm, 4, "/depth_threshold_mm")});
  t.rows.push_back({"max depth (mm)", number(w.max_depth_mm, 4, "/max_depth_mm")});
  t.rows.push_back({"bias offset (mm)", number(w.damage.bias_offset_mm, 4, "/bias/offset_mm")});
  t.rows.push_back({"bias tilt (deg)", number(w.damage.bias_tilt_deg, 4, "/bias/tilt_deg")});
  t.rows.push_back({"rims", count(w.rims.size())});
  t.rows.push_back({"damage covered by layer 1 (%)", number(w.damage_coverage_pct, 2, "/damage_coverage_pct")});
  t.rows.push_back({"paths", count(w.paths.size(), "/paths")});
  t.rows.push_back({"total length (mm)", number(w.total_length_mm, 3, "/total_length_mm")});
  t.rows.push_back({"spacing error max (%)", number(w.spacing_error_pct_max, 4, "/spacing_error_pct_max")});
  t.rows.push_back({"chord error max (mm)", number(w.chord_error_mm_max, 6, "/chord_error_mm_max")});
  return t;
}

html::Table crater_table(const DamageMap& d) {
  html::Table t{
      "Craters", {"crater", "depth (mm)", "area (mm^2)", "volume (mm^3)", "deepest at (mm)", "at the border"}, {}};
  for (std::size_t k = 0; k < d.regions.size(); ++k) {
    const DamageRegion& r = d.regions[k];
    const std::string at = "/craters/" + std::to_string(k) + "/";
    char where[96];
    std::snprintf(where, sizeof where, "%.1f, %.1f, %.1f", r.deepest.x(), r.deepest.y(), r.deepest.z());
    t.rows.push_back({count(static_cast<std::size_t>(r.id), at + "id"), number(r.max_depth_mm, 3, at + "max_depth_mm"),
                      number(r.area_mm2, 1, at + "area_mm2"), number(r.volume_mm3, 1, at + "volume_mm3"), where,
                      r.at_border ? "yes" : "no"});
  }
  return t;
}

html::Table layer_table(const WeldLayersReportFigures& f) {
  html::Table t{"Layers", {"layer", "paths", "length (mm)", "coverage (%)"}, {}};
  for (std::size_t k = 0; k < f.layers.size(); ++k) {
    const WeldLayerFigure& l = f.layers[k];
    t.rows.push_back({count(static_cast<std::size_t>(l.layer)),
                      count(l.paths.size(), "/paths_per_layer/" + std::to_string(k)), number(l.length_mm, 3),
                      number(l.coverage_pct, 2, "/coverage_pct_by_layer/" + std::to_string(k))});
  }
  return t;
}

html::Plot coverage_plot(const WeldLayersReportFigures& f, double min_coverage_pct) {
  html::Plot p = detail::line_plot("Coverage by layer", "layer", "coverage (%)");
  html::Series s = detail::series("coverage", {}, {}, html::kBlue, true);
  for (const WeldLayerFigure& l : f.layers) s.x.push_back(l.layer), s.y.push_back(l.coverage_pct);
  p.series.push_back(s);
  p.y_band = detail::band(min_coverage_pct, 100.0, "at least --min-coverage");
  return p;
}

void add_scene(const WeldLayersReportFigures& f, const WeldLayerResult& w, html::Scene* scene) {
  if (!f.surface.faces.empty()) {
    const double threshold = w.depth_threshold_mm;
    const double deepest = std::max(w.max_depth_mm, threshold + 1e-3);
    std::vector<html::Rgb> colours;
    for (const double d : f.depth_mm) colours.push_back(depth_colour(d, threshold, deepest));
    html::SceneObject& surface =
        scene->add_mesh("eroded surface", f.surface.vertices, f.surface.faces, html::kGrey, 1.0, colours);
    surface.values = f.depth_mm;
    surface.value_label = "depth (mm)";
    scene->set_colour_bar(html::make_colour_bar("depth below the reference (mm)",
                                                "grey above the threshold, "
                                                "yellow to dark red",
                                                0.0, deepest,
                                                [&](double d) { return depth_colour(d, threshold, deepest); }));
  }
  if (!f.rims.empty()) scene->add_polylines("rims", f.rims, html::kRed);
  for (const DamageRegion& r : w.damage.regions) {
    char label[64];
    std::snprintf(label, sizeof label, "crater %d: %.3f mm deep", r.id, r.max_depth_mm);
    scene->add_callout(r.deepest, label);
  }
  for (const WeldLayerFigure& l : f.layers) {
    scene->add_polylines("layer " + std::to_string(l.layer), l.paths, kLayerColours[(l.layer - 1) % 6]);
  }
}

}  // namespace

html::Rgb depth_colour(double depth_mm, double threshold_mm, double max_depth_mm) {
  if (!(depth_mm > threshold_mm)) return {215, 215, 215};
  const double u = std::min(1.0, (depth_mm - threshold_mm) / std::max(1e-12, max_depth_mm - threshold_mm));
  // yellow (255, 220, 0) -> dark red (150, 0, 0)
  const auto mix = [u](double a, double b) { return static_cast<std::uint8_t>(std::lround(a + (b - a) * u)); };
  return {mix(255, 150), mix(220, 0), 0};
}

WeldLayersReportFigures weld_layers_report_figures(const WeldLayersJobResult& job, std::size_t max_nodes) {
  WeldLayersReportFigures f;
  add_surface(job, max_nodes, &f);
  const WeldLayerResult& w = job.weld;
  for (const IntersectionCurve& rim : w.rims) {
    std::vector<Eigen::Vector3d> line;
    for (const IntersectionPoint& p : rim.points) line.push_back(p.position);
    if (rim.closed && !line.empty()) line.push_back(line.front());
    f.rims.push_back(line);
  }
  for (int k = 1; k <= w.layers; ++k) {
    WeldLayerFigure layer;
    layer.layer = k;
    if (static_cast<std::size_t>(k) <= w.coverage_pct.size())
      layer.coverage_pct = w.coverage_pct[static_cast<std::size_t>(k - 1)];
    f.layers.push_back(layer);
  }
  for (const WeldPath& p : w.paths) {
    if (p.layer < 1 || p.layer > w.layers) continue;
    WeldLayerFigure& layer = f.layers[static_cast<std::size_t>(p.layer - 1)];
    layer.paths.push_back(p.points);
    layer.length_mm += p.length_mm();
  }
  return f;
}

html::Page weld_layers_report(const WeldLayersJobOptions& options, const WeldLayersJobResult& job) {
  const WeldLayerResult& w = job.weld;
  html::Page page;
  page.job = "weld-layers";
  page.inputs = {
      {options.eroded_path, std::to_string(job.eroded_rows) + " x " + std::to_string(job.eroded_cols) + " grid"}};
  if (!options.reference_path.empty()) {
    page.inputs.push_back({options.reference_path,
                           std::to_string(job.reference_rows) + " x " + std::to_string(job.reference_cols) + " grid"});
  }
  page.options = options_json(options);
  page.verdict = w.ok ? html::Verdict{w.warnings.empty() ? html::Level::kOk : html::Level::kCheck,
                                      std::to_string(w.layers) + " layers, " + std::to_string(w.paths.size()) +
                                          " paths; damage covered " +
                                          std::to_string(std::lround(w.damage_coverage_pct)) + " % by layer 1"}
                      : html::Verdict{html::Level::kFail, w.termination + "; no file written"};
  page.warnings = w.warnings;
  page.result = weld_layers_json(options, job);
  const WeldLayersReportFigures f = weld_layers_report_figures(job);
  add_scene(f, w, &page.scene);
  html::Section figures{"Figures", {}, {damage_table(w), crater_table(w.damage)}, {}};
  if (!f.layers.empty()) {
    figures.tables.push_back(layer_table(f));
    figures.plots.push_back(coverage_plot(f, options.weld.min_coverage_pct));
  }
  page.sections.push_back(figures);
  return page;
}

}  // namespace conform
