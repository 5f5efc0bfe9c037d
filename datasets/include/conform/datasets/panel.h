#pragma once
// `generate plate` / `generate nosecone`: a deformed panel with an opening, its scan and its deburring trajectory,
// with the ground truth (panel_options.h describes the shapes and the deformation).
//
//   PanelOptions options;  options.shape = PanelShape::kNoseCone;  options.seed = 7;
//   const PanelData panel = generate_panel(options);
//   // panel.surface, panel.contour, panel.trajectory: nominal; panel.scan, panel.truth: deformed

#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cloud.h"
#include "conform/core/mesh.h"
#include "conform/core/polyline.h"
#include "conform/datasets/panel_options.h"

namespace conform {

// Tool positions with their unit tool normals, in order.
struct PanelPath {
  std::vector<Eigen::Vector3d> points;   // mm
  std::vector<Eigen::Vector3d> normals;  // unit
};

struct PanelData {
  PanelOptions options;  // as given, without the progress callback
  // Nominal (panel frame): the surface within band_mm of the opening plus the opening's flank (faces wound so that
  // normals point away from the material), the opening's top edge (closed, about contour_spacing apart) and the
  // deburring trajectory along that edge with the surface normal as tool normal.
  Mesh surface;
  Polyline contour;
  PanelPath trajectory;
  // Deformed: the scan (noisy points, no normals) and the trajectory's exact image with its deformed normals.
  Cloud scan;
  PanelPath truth;
  double perimeter_mm = 0.0;                            // the contour's length
  std::vector<std::pair<double, double>> missing_arcs;  // (start, length) of each missing arc, mesh parameter tau
  std::size_t scan_points_removed = 0;                  // by the missing arcs and holes
};

// Throws conform::Error when the options are not valid.
PanelData generate_panel(const PanelOptions& options);

}  // namespace conform
