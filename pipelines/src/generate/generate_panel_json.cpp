#include "conform/pipelines/generate/generate_panel_json.h"

#include "conform/core/error.h"

namespace conform {

PlateOpening plate_opening(const std::string& text) {
  if (text == "ellipse") return PlateOpening::kEllipse;
  if (text == "rectangle") return PlateOpening::kRoundedRectangle;
  throw Error("--opening " + text + ": use ellipse or rectangle");
}

nlohmann::json generate_panel_json(const GeneratePanelResult& r) {
  return {{"scan", r.files.scan},
          {"nominal", r.files.nominal},
          {"contour", r.files.contour},
          {"trajectory", r.files.trajectory},
          {"truth_trajectory", r.files.truth_trajectory},
          {"truth_file", r.files.truth_json},
          {"scan_points", r.scan_points},
          {"contour_points", r.contour_points},
          {"trajectory_rows", r.trajectory_rows},
          {"surface_vertices", r.surface_vertices},
          {"surface_faces", r.surface_faces},
          {"perimeter_mm", r.perimeter_mm},
          {"truth", r.truth}};
}

}  // namespace conform
