#pragma once
// `conform generate tube`: a synthetic tube scan (datasets/tube.h) written as a mesh, with its ground truth as JSON
// beside it (foo.ply -> foo.truth.json, keys in datasets/tube_json.h and docs/generate.md). Both files appear, or
// neither does; the same options give the same bytes.

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "conform/core/io.h"
#include "conform/datasets/tube.h"

namespace conform {

struct GenerateTubeOptions {
  TubeOptions tube;                       // its progress callback reports the generation
  std::string out_path;                   // the mesh, .ply or .stl (case-insensitive)
  Encoding encoding = Encoding::kBinary;  // binary or ascii .ply/.stl
  bool double_precision = false;          // .ply vertices as double (the exact truth on disk); float otherwise

  // False (and why) when the path is not .ply/.stl or the tube options are not valid.
  bool IsValid(std::string* error) const;
};

struct GenerateTubeResult {
  std::string mesh_path;
  std::string truth_path;
  std::size_t vertices = 0;
  std::size_t faces = 0;
  std::size_t holes = 0;     // holes cut, given and random
  std::size_t outliers = 0;  // vertices moved as outliers
  double surface_area_mm2 = 0.0;
  nlohmann::json truth;  // what truth_path holds
};

// foo.ply -> foo.truth.json (the extension replaced, whatever its case).
std::string tube_truth_path(const std::string& mesh_path);

// Throws conform::Error naming the option or the file: invalid options, an extension other than .ply/.stl, a file
// that cannot be written. A failure leaves neither file behind.
GenerateTubeResult run_generate_tube(const GenerateTubeOptions& options);

}  // namespace conform
