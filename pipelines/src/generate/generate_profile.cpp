#include "conform/pipelines/generate/generate_profile.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/output_set.h"

namespace conform {
namespace {

std::string points_csv(const std::vector<Eigen::Vector3d>& points) {
  CsvWriter csv({"x_mm", "y_mm", "z_mm"}, 6);
  for (const Eigen::Vector3d& p : points) {
    csv.cell(p.x()).cell(p.y()).cell(p.z());
    csv.end_row();
  }
  return csv.text();
}

std::string features_csv(const ProfileScan& scan) {
  CsvWriter csv({"id", "type", "tx_mm", "ty_mm", "radius_mm"}, 6);
  for (const ProfileDesignRow& row : scan.features) {
    csv.cell(row.id).cell(row.type).cell(row.tx_mm).cell(row.ty_mm).cell(row.radius_mm);
    csv.end_row();
  }
  return csv.text();
}

std::string truth_csv(const ProfileScan& scan) {
  CsvWriter csv({"id", "i", "tx_mm", "ty_mm", "x_mm", "y_mm", "z_mm"}, 6);
  for (const ProfileTruthRow& row : scan.truth) {
    csv.cell(row.id).cell(row.i).cell(row.tx_mm).cell(row.ty_mm);
    csv.cell(row.position.x()).cell(row.position.y()).cell(row.position.z());
    csv.end_row();
  }
  return csv.text();
}

nlohmann::json truth_json(const ProfileScanOptions& o, const GenerateProfileResult& r) {
  const ProfileDeformationOptions& d = o.deformation;
  const auto name = [](const std::string& path) { return std::filesystem::path(path).filename().string(); };
  return {{"length_mm", d.length_mm},
          {"width_mm", d.width_mm},
          {"bow_in_plane_mm", d.bow_in_plane_mm},
          {"bow_asymmetry", d.bow_asymmetry},
          {"bow_out_of_plane_mm", d.bow_out_of_plane_mm},
          {"twist_deg", d.twist_rad * 180.0 / M_PI},
          {"kink_deg", d.kink_rad * 180.0 / M_PI},
          {"kink_at_mm", d.kink_at_mm},
          {"kink_length_mm", d.kink_length_mm},
          {"spacing_mm", o.spacing_mm},
          {"noise_mm", o.noise_mm},
          {"dropout_fraction", o.dropout_fraction},
          {"dropped", r.dropped},
          {"edge_points", r.edge_points},
          {"holes", o.holes},
          {"hole_radius_mm", o.hole_radius_mm},
          {"hole_tx_mm", o.hole_tx_mm},
          {"marking_line", o.marking_line},
          {"outliers", o.outliers},
          {"outlier_mm", o.outlier_mm},
          {"offset_mm", {o.offset_mm.x(), o.offset_mm.y(), o.offset_mm.z()}},
          {"reversed", o.reversed},
          {"seed", o.seed},
          {"frame", "flat profile: edge along +x from the origin, web towards +y (Tx), web normal +z"},
          {"edge_file", name(r.edge_path)},
          {"second_edge_file",
           r.second_edge_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(name(r.second_edge_path))},
          {"features_file", name(r.features_path)},
          {"truth_file", name(r.truth_path)}};
}

}  // namespace

bool GenerateProfileOptions::IsValid(std::string* error) const {
  std::string why;
  if (out_path.empty()) {
    why = "no output path: give the edge CSV to write (--out FILE.csv)";
  } else if (std::filesystem::path(out_path).extension() != ".csv") {
    why = out_path + ": the measured edge is written as .csv";
  } else if (!scan.IsValid(&why)) {
    why = "generate profile: " + why;
  }
  if (error != nullptr) *error = why;
  return why.empty();
}

std::string profile_sibling_path(const std::string& edge_path, const std::string& suffix) {
  return std::filesystem::path(edge_path).replace_extension(suffix).string();
}

GenerateProfileResult run_generate_profile(const GenerateProfileOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  const ProfileScan scan = generate_profile_scan(options.scan);
  GenerateProfileResult r;
  r.edge_path = options.out_path;
  if (options.scan.second_edge) r.second_edge_path = profile_sibling_path(options.out_path, ".edge2.csv");
  r.features_path = profile_sibling_path(options.out_path, ".features.csv");
  r.truth_path = profile_sibling_path(options.out_path, ".truth.csv");
  r.truth_json_path = profile_sibling_path(options.out_path, ".truth.json");
  r.edge_points = scan.edge.size();
  r.dropped = scan.dropped;
  for (std::size_t k = 0; k < scan.features.size(); ++k) {
    if (k == 0 || scan.features[k].id != scan.features[k - 1].id) ++r.features;  // a feature's rows are consecutive
  }
  r.truth = truth_json(options.scan, r);

  std::vector<std::pair<std::string, std::string>> files = {{r.edge_path, points_csv(scan.edge)},
                                                            {r.features_path, features_csv(scan)},
                                                            {r.truth_path, truth_csv(scan)},
                                                            {r.truth_json_path, r.truth.dump(2) + "\n"}};
  if (!r.second_edge_path.empty()) files.emplace_back(r.second_edge_path, points_csv(scan.second_edge));
  OutputSet outputs;  // one file without the others is half an output: all or none
  for (const auto& [path, text] : files) write_file_atomically(path, text);
  outputs.commit();
  return r;
}

}  // namespace conform
