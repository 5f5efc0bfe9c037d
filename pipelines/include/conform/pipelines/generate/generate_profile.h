#pragma once
// `conform generate profile`: a deformed ship profile as a laser sensor measures it (datasets/profile.h), written as
// the files `conform profile` reads, with its ground truth beside them. For --out foo.csv:
//
//   foo.csv             the measured edge: x_mm,y_mm,z_mm in measuring order (the origin first)
//   foo.edge2.csv       the second edge (Tx = width), when asked for
//   foo.features.csv    the designed features: id,type,tx_mm,ty_mm,radius_mm
//   foo.truth.csv       where each designed point lies on the deformed profile: id,i,tx_mm,ty_mm,x_mm,y_mm,z_mm
//                       (circle centres i = -1, vertices i = 0, 1, ...)
//   foo.truth.json      every parameter (units in the keys), the seed, the frame, the file names
//
// All appear or none does; the same options give the same bytes.

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "conform/datasets/profile.h"

namespace conform {

struct GenerateProfileOptions {
  ProfileScanOptions scan;
  std::string out_path;  // the edge CSV; the other files are named after it

  bool IsValid(std::string* error) const;
};

struct GenerateProfileResult {
  std::string edge_path;
  std::string second_edge_path;  // empty without a second edge
  std::string features_path;
  std::string truth_path;
  std::string truth_json_path;
  std::size_t edge_points = 0;
  std::size_t dropped = 0;
  std::size_t features = 0;  // designed features (a polyline's rows count once)
  nlohmann::json truth;      // what truth_json_path holds
};

// foo.csv -> foo<suffix> (the extension replaced): ".features.csv", ".truth.csv", ".truth.json", ".edge2.csv".
std::string profile_sibling_path(const std::string& edge_path, const std::string& suffix);

// Throws conform::Error naming the option or the file; a failure leaves none of the files behind.
GenerateProfileResult run_generate_profile(const GenerateProfileOptions& options);

}  // namespace conform
