#include "conform/pipelines/weld_layers/weld_layers.h"

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/fitting/bezier_network.h"
#include "conform/fitting/coons_patch.h"
#include "conform/fitting/surface_grid.h"

namespace conform {
namespace {

SurfaceGrid read_grid(const std::string& path) {
  SurfaceGrid grid = surface_grid_from_table(read_csv(path, {"row", "col", "x_mm", "y_mm", "z_mm"}));
  const double nodes = static_cast<double>(grid.rows) * static_cast<double>(grid.cols);
  if (nodes > static_cast<double>(kMaxWeldGridNodes)) {
    throw Error(path + ": a " + std::to_string(grid.rows) + " x " + std::to_string(grid.cols) + " grid exceeds " +
                std::to_string(kMaxWeldGridNodes) + " nodes (limit kMaxWeldGridNodes): crop or thin it");
  }
  return grid;
}

}  // namespace

WeldLayersJobResult run_weld_layers(const WeldLayersJobOptions& options) {
  std::string error;
  if (!options.weld.IsValid(&error)) throw Error("weld-layers: " + error);
  const SurfaceGrid eroded = read_grid(options.eroded_path);
  const SurfaceGrid reference = options.reference_path.empty()
                                    ? coons_patch_of_border(eroded).sample(eroded.rows, eroded.cols)
                                    : read_grid(options.reference_path);
  WeldLayersJobResult result;
  result.eroded_rows = eroded.rows, result.eroded_cols = eroded.cols;
  result.reference_rows = reference.rows, result.reference_cols = reference.cols;
  if (options.keep_geometry) result.eroded = eroded;
  result.weld = plan_weld_layers(BezierNetwork(eroded), BezierNetwork(reference), options.weld);
  if (result.weld.ok && !options.out_path.empty()) {
    write_file_atomically(options.out_path, weld_layers_csv(result.weld));
    result.out_path = options.out_path;
  }
  return result;
}

std::string weld_layers_csv(const WeldLayerResult& result) {
  std::string text = "layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz\n";
  for (const WeldPath& path : result.paths) {
    for (std::size_t i = 0; i < path.points.size(); ++i) {
      const Eigen::Vector3d& p = path.points[i];
      const Eigen::Vector3d& n = path.normals[i];
      text += std::to_string(path.layer) + "," + std::to_string(path.path) + "," + std::to_string(i) + "," +
              format_fixed(p.x(), 6) + "," + format_fixed(p.y(), 6) + "," + format_fixed(p.z(), 6) + "," +
              format_fixed(n.x(), 9) + "," + format_fixed(n.y(), 9) + "," + format_fixed(n.z(), 9) + "\n";
    }
  }
  return text;
}

}  // namespace conform
