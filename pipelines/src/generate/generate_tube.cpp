#include "conform/pipelines/generate/generate_tube.h"

#include <cstdio>
#include <filesystem>

#include "conform/core/atomic_file.h"
#include "conform/core/error.h"
#include "conform/core/output_set.h"
#include "conform/datasets/tube_json.h"

namespace conform {

bool GenerateTubeOptions::IsValid(std::string* error) const {
  std::string why;
  const std::string extension = file_extension(out_path);
  if (out_path.empty()) {
    why = "no output path: give the mesh file to write (.ply or .stl)";
  } else if (extension != ".ply" && extension != ".stl") {
    why = out_path + ": a tube mesh is written as .ply or .stl, not " +
          (extension.empty() ? std::string("a file without extension") : "'" + extension + "'");
  } else if (!tube.IsValid(&why)) {
    why = "tube options: " + why;
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

std::string tube_truth_path(const std::string& mesh_path) {
  return std::filesystem::path(mesh_path).replace_extension(".truth.json").string();
}

GenerateTubeResult run_generate_tube(const GenerateTubeOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);

  const TubeScan scan = generate_tube(options.tube);
  GenerateTubeResult result;
  result.mesh_path = options.out_path;
  result.truth_path = tube_truth_path(options.out_path);
  result.vertices = scan.mesh.vertices.size();
  result.faces = scan.mesh.faces.size();
  result.holes = scan.truth.holes.size();
  result.outliers = scan.truth.outlier_indices.size();
  result.surface_area_mm2 = surface_area(scan.mesh);
  result.truth = tube_truth_json(scan);
  // Only the file name: the same arguments in another directory give the same bytes.
  result.truth["mesh_file"] = std::filesystem::path(options.out_path).filename().string();
  result.truth["mesh_encoding"] = options.encoding == Encoding::kBinary ? "binary" : "ascii";
  result.truth["mesh_double_precision"] = options.double_precision;

  const ProgressFn& progress = options.tube.progress;
  report(progress, "write mesh", 0.0);
  WriteOptions write;
  write.encoding = options.encoding;
  write.double_precision = options.double_precision;
  OutputSet outputs;  // a mesh without its truth is half an output: both or neither
  write_mesh(result.mesh_path, scan.mesh, write);
  report(progress, "write mesh", 1.0);
  write_file_atomically(result.truth_path, result.truth.dump(2) + "\n");
  outputs.commit();
  return result;
}

}  // namespace conform
