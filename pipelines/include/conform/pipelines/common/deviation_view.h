#pragma once
// The deviation part of a report (compare, align): the scan's points coloured by signed deviation with the colour
// scale of the deviation map (deviation_colours.h) and its colour bar with the tolerance band, the reference mesh
// semi-transparent, callouts at the (up to 5, 10 % of the extent apart) largest |deviations|, and a "Deviation" section with the
// statistics table, the callouts' table and the histogram (as the PNG's: 60 bins over the 0.5th to 99.5th
// percentile without far outliers, 0 and the band; the rest in the end bars, labelled). A click on a scan point
// shows its coordinates and deviation.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/evaluation/statistics.h"
#include "conform/report/page.h"

namespace conform::html {

struct DeviationView {
  std::string scan_name = "scan";            // the layers' names
  std::string reference_name = "reference";
  double reference_opacity = 0.45;
  // Tie the statistics cells to the page's JSON: the pointer of each figure is this prefix + "/mean_mm" etc.
  // (compare's keys); unset: not tied (the figures are not in the job's JSON).
  bool tie_to_json = true;
  std::string json_prefix;
  std::string title = "Deviation";
  std::string quantity = "deviation";  // the colour bar's and the histogram's label, "residual" for a fit
};

// Adds the layers to page.scene and the section to page.sections. `points` and `deviation_mm` one to one (NaN:
// unmatched, grey); `reference` with faces is drawn as a mesh, without as grey points.
void add_deviation_view(Page& page, const std::vector<Eigen::Vector3d>& points, const std::vector<double>& deviation_mm,
                        const DeviationStatistics& statistics, const Mesh& reference, const DeviationView& view = {});

}  // namespace conform::html
