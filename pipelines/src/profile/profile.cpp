#include "conform/pipelines/profile/profile.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <nlohmann/json.hpp>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/input_file.h"

namespace conform {
namespace {

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

bool needs_radius(ProfileFeatureType type) {
  return type == ProfileFeatureType::kCircle || type == ProfileFeatureType::kSlot;
}

std::vector<ProfileFeature> read_features_csv(const std::string& path) {
  const CsvTable table = read_csv(path, {"id", "type", "tx_mm", "ty_mm"});
  const std::size_t id = table.column("id"), type = table.column("type");
  const std::size_t tx = table.column("tx_mm"), ty = table.column("ty_mm");
  const bool has_radius = table.has_column("radius_mm");
  std::vector<ProfileFeature> features;
  std::unordered_map<std::string, std::size_t> seen;  // id -> feature index: O(n) for n rows, not O(n^2)
  for (std::size_t row = 0; row < table.rows(); ++row) {
    const std::string where = path + ":" + std::to_string(table.line_numbers[row]);
    const std::string& name = table.text(row, id);
    if (name.empty()) throw Error(where + ": empty id");
    ProfileFeatureType kind;
    if (!parse_profile_feature_type(table.text(row, type), &kind)) {
      throw Error(where + ": unknown feature type '" + table.text(row, type) +
                  "' (point, circle, slot, polyline or polygon)");
    }
    const Eigen::Vector2d vertex(table.number(row, tx), table.number(row, ty));
    if (!features.empty() && features.back().id == name) {
      if (features.back().type != kind) {
        throw Error(where + ": feature '" + name + "' continues as " + to_string(kind) + " but began as " +
                    to_string(features.back().type));
      }
      features.back().vertices.push_back(vertex);
      continue;
    }
    const auto [it, fresh] = seen.emplace(name, features.size());
    if (!fresh) {
      throw Error(where + ": id '" + name + "' comes back after other features (" + features[it->second].where + ")");
    }
    ProfileFeature f;
    f.id = name;
    f.type = kind;
    f.where = where;
    f.vertices = {vertex};
    if (needs_radius(kind)) {
      if (!has_radius) throw Error(where + ": a " + std::string(to_string(kind)) + " needs the column radius_mm");
      f.radius_mm = table.number(row, table.column("radius_mm"));
    }
    features.push_back(f);
  }
  return features;
}

double json_number(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j.at(key).is_number()) throw Error(where + ": '" + key + "' must be a number");
  const double value = j.at(key).get<double>();
  if (!std::isfinite(value)) throw Error(where + ": '" + key + "' is not a finite number");
  return value;
}

ProfileFeature feature_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw Error(where + ": a feature must be a JSON object");
  ProfileFeature f;
  f.where = where;
  if (!j.contains("id") || !j.at("id").is_string()) throw Error(where + ": 'id' must be a string");
  f.id = j.at("id").get<std::string>();
  const std::string type = j.contains("type") && j.at("type").is_string() ? j.at("type").get<std::string>() : "";
  if (!parse_profile_feature_type(type, &f.type)) {
    throw Error(where + ": unknown feature type '" + type + "' (point, circle, slot, polyline or polygon)");
  }
  if (j.contains("points_mm")) {
    for (const nlohmann::json& p : j.at("points_mm")) {
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
        throw Error(where + ": 'points_mm' must hold [tx_mm, ty_mm] pairs");
      }
      f.vertices.emplace_back(p[0].get<double>(), p[1].get<double>());
      if (!f.vertices.back().allFinite()) throw Error(where + ": 'points_mm' holds a number that is not finite");
    }
  } else {
    f.vertices = {{json_number(j, "tx_mm", where), json_number(j, "ty_mm", where)}};
  }
  if (needs_radius(f.type)) f.radius_mm = json_number(j, "radius_mm", where);
  return f;
}

std::vector<ProfileFeature> read_features_json(const std::string& path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_input_file(path));
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for a number such as 1e400
    throw Error(path + ": not valid JSON: " + e.what());
  }
  if (!j.is_object() || !j.contains("features") || !j.at("features").is_array()) {
    throw Error(path + ": expected an object with a 'features' array");
  }
  std::vector<ProfileFeature> features;
  std::unordered_set<std::string> seen;
  for (std::size_t k = 0; k < j.at("features").size(); ++k) {
    const std::string where = path + ": features[" + std::to_string(k) + "]";
    try {
      features.push_back(feature_from_json(j.at("features")[k], where));
    } catch (const nlohmann::json::exception& e) {
      throw Error(where + ": " + e.what());
    }
    if (!seen.insert(features.back().id).second) throw Error(where + ": id '" + features.back().id + "' repeats");
  }
  return features;
}

}  // namespace

std::vector<Eigen::Vector3d> read_profile_edge(const std::string& path) {
  const CsvTable table = read_csv(path, {"x_mm", "y_mm", "z_mm"});
  const Eigen::MatrixXd xyz = table.numbers({"x_mm", "y_mm", "z_mm"});
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(xyz.rows()));
  for (Eigen::Index i = 0; i < xyz.rows(); ++i) points[static_cast<std::size_t>(i)] = xyz.row(i).transpose();
  return points;
}

std::vector<ProfileFeature> read_profile_features(const std::string& path) {
  const std::string ext = lower_extension(path);
  std::vector<ProfileFeature> features;
  if (ext == ".csv") {
    features = read_features_csv(path);
  } else if (ext == ".json") {
    features = read_features_json(path);
  } else {
    throw Error(path + ": features are read from .csv or .json, not '" + ext + "'");
  }
  if (features.empty()) throw Error(path + ": no features");
  for (const ProfileFeature& f : features) f.validate();
  return features;
}

std::string profile_csv(const ProfileCompensationResult& result) {
  CsvWriter csv({"id", "i", "tx_mm", "ty_mm", "x_mm", "y_mm", "z_mm", "nx", "ny", "nz", "dx", "dy", "dz"}, 6);
  const auto row = [&csv](const std::string& id, int i, const Eigen::Vector2d& designed, const Eigen::Vector3d& p,
                          const Eigen::Vector3d& normal, const Eigen::Vector3d& cut) {
    csv.cell(id).cell(i).cell(designed.x()).cell(designed.y()).cell(p.x()).cell(p.y()).cell(p.z());
    csv.cell(normal.x()).cell(normal.y()).cell(normal.z()).cell(cut.x()).cell(cut.y()).cell(cut.z());
    csv.end_row();
  };
  for (const ProfileFeatureResult& f : result.features) {
    if (f.has_centre) row(f.id, -1, f.designed_centre, f.centre, f.centre_normal, f.centre_direction);
    for (std::size_t k = 0; k < f.mapped.size(); ++k) {
      row(f.id, static_cast<int>(k), f.designed[k], f.mapped[k], f.normals[k], f.directions[k]);
    }
  }
  return csv.text();
}

ProfileJobResult run_profile(const ProfileJobOptions& options) {
  if (options.edge_path.empty()) throw Error("profile: no edge file (--edge FILE.csv)");
  if (options.features_path.empty()) throw Error("profile: no features file (--features FILE.csv|.json)");
  std::string problem;
  if (!options.compensation.IsValid(&problem)) throw Error("profile: " + problem);
  ProfileJobResult job;
  const std::vector<Eigen::Vector3d> edge = read_profile_edge(options.edge_path);
  const std::vector<ProfileFeature> features = read_profile_features(options.features_path);
  std::vector<Eigen::Vector3d> second;
  if (!options.second_edge_path.empty()) second = read_profile_edge(options.second_edge_path);
  job.edge_points = edge.size();
  job.second_edge_points = second.size();
  job.compensation =
      compensate_profile(edge, features, options.compensation, options.second_edge_path.empty() ? nullptr : &second,
                         options.edge_path, options.second_edge_path);
  if (options.keep_geometry) job.edge = edge, job.second_edge = second;
  const std::string text = profile_csv(job.compensation);
  job.out_rows = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) - 1;
  if (!options.out_path.empty() && job.compensation.ok) {
    write_file_atomically(options.out_path, text);
    job.out_path = options.out_path;
  }
  return job;
}

}  // namespace conform
