#pragma once
// `conform generate eroded`: a synthetic eroded blade (datasets/eroded.h) written as grid files: the eroded grid at
// out_path (CSV row,col,x_mm,y_mm,z_mm), the reference grid beside it (foo.csv -> foo.reference.csv) and the ground-
// truth crater rims (foo.rims.csv: crater,i,x_mm,y_mm,z_mm). All three appear, or none does; same options, same bytes.

#include <string>

#include "conform/datasets/eroded.h"

namespace conform {

struct GenerateErodedOptions {
  ErodedOptions eroded;
  std::string out_path;  // the eroded grid, .csv
};

struct GenerateErodedResult {
  std::string eroded_path;
  std::string reference_path;
  std::string rims_path;
  int rows = 0, cols = 0;
  std::size_t craters = 0;
  double max_depth_mm = 0.0;
};

// foo.csv -> foo.<kind>.csv
std::string eroded_sibling_path(const std::string& out_path, const std::string& kind);

// Throws conform::Error naming the option or the file; a failure leaves none of the three files behind.
GenerateErodedResult run_generate_eroded(const GenerateErodedOptions& options);

}  // namespace conform
