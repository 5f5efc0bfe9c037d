#include "conform/pipelines/weld_layers_report.h"

#include <algorithm>
#include <cmath>

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

}  // namespace

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
    if (static_cast<std::size_t>(k) <= w.coverage_pct.size()) layer.coverage_pct = w.coverage_pct[static_cast<std::size_t>(k - 1)];
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

}  // namespace conform
