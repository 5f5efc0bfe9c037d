#pragma once
// The report of `conform weld-layers --report FILE.html` (issue 21): the eroded surface coloured by its depth below
// the reference, the rims (the damage's boundary), and each layer's paths (one object per layer, so that a layer can
// be shown alone); coverage, paths and length by layer as a table and a plot.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/pipelines/weld_layers/weld_layers.h"
#include "conform/report/page.h"

namespace conform {

// The surface is drawn through at most about this many grid nodes (every k-th row and column).
constexpr std::size_t kWeldLayersReportNodes = 60000;

struct WeldLayerFigure {
  int layer = 0;  // 1-based
  std::vector<std::vector<Eigen::Vector3d>> paths;
  double length_mm = 0.0;
  double coverage_pct = 0.0;  // WeldLayerResult::coverage_pct of this layer
};

struct WeldLayersReportFigures {
  Mesh surface;                  // the eroded grid (thinned), two triangles per cell; empty without keep_geometry
  std::vector<double> depth_mm;  // per surface vertex: depth below the reference (DamageMap::depth)
  int stride = 1;                // every stride-th row and column of the grid
  std::vector<std::vector<Eigen::Vector3d>> rims;  // a closed rim ends on its first point
  std::vector<WeldLayerFigure> layers;             // layer 1, 2, ...
};

// max_nodes: the surface's limit (every k-th row and column, and the last, so that about this many remain).
WeldLayersReportFigures weld_layers_report_figures(const WeldLayersJobResult& job,
                                                   std::size_t max_nodes = kWeldLayersReportNodes);

// The colour of a depth below the reference: light grey above the threshold (not damage), then a ramp from yellow to
// dark red at max_depth_mm.
html::Rgb depth_colour(double depth_mm, double threshold_mm, double max_depth_mm);

// The page: header (inputs, options, verdict: ok, or the termination), the surface coloured by depth with its colour
// bar, the rims and every layer's paths (a run with keep_geometry for the surface), the craters and the layers as
// tables (cells tied to weld_layers_json), coverage and length by layer. Page::date is left to the caller.
html::Page weld_layers_report(const WeldLayersJobOptions& options, const WeldLayersJobResult& job);

}  // namespace conform
