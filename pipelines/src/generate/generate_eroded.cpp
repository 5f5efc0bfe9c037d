#include "conform/pipelines/generate/generate_eroded.h"

#include <cstdio>

#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/output_set.h"
#include "conform/fitting/surface_grid.h"

namespace conform {

std::string eroded_sibling_path(const std::string& out_path, const std::string& kind) {
  const std::size_t slash = out_path.find_last_of('/');
  const std::size_t dot = out_path.find_last_of('.');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? out_path.substr(0, dot) : out_path) + "." + kind + ".csv";
}

GenerateErodedResult run_generate_eroded(const GenerateErodedOptions& options) {
  if (options.out_path.empty()) throw Error("generate eroded: give an output file (--out FILE.csv)");
  const ErodedScan scan = generate_eroded(options.eroded);
  GenerateErodedResult result;
  result.eroded_path = options.out_path;
  result.reference_path = eroded_sibling_path(options.out_path, "reference");
  result.rims_path = eroded_sibling_path(options.out_path, "rims");
  result.rows = scan.rows;
  result.cols = scan.cols;
  result.craters = scan.rims.size();
  result.max_depth_mm = scan.max_depth_mm;
  SurfaceGrid eroded{scan.rows, scan.cols, scan.eroded}, reference{scan.rows, scan.cols, scan.reference};
  CsvWriter rims({"crater", "i", "x_mm", "y_mm", "z_mm"});
  for (std::size_t k = 0; k < scan.rims.size(); ++k) {
    for (std::size_t i = 0; i < scan.rims[k].size(); ++i) {
      const Eigen::Vector3d& p = scan.rims[k][i];
      rims.cell(static_cast<int>(k + 1)).cell(static_cast<int>(i)).cell(p.x()).cell(p.y()).cell(p.z());
      rims.end_row();
    }
  }
  OutputSet outputs;  // the three files, all or none
  surface_grid_table(eroded).write(result.eroded_path);
  surface_grid_table(reference).write(result.reference_path);
  rims.write(result.rims_path);
  outputs.commit();
  return result;
}

}  // namespace conform
