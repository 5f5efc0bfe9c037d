#include "conform/pipelines/generate/generate_panel.h"

#include <cstdio>
#include <filesystem>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/output_set.h"

namespace conform {
namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json options_json(const PanelOptions& o) {
  nlohmann::json j = {{"shape", to_string(o.shape)},
                      {"band_mm", o.band_mm},
                      {"thickness_mm", o.thickness_mm},
                      {"surface_edge_mm", o.surface_edge_mm},
                      {"contour_spacing_mm", o.contour_spacing_mm},
                      {"trajectory_spacing_mm", o.trajectory_spacing_mm},
                      {"noise_mm", o.noise_mm},
                      {"missing_fraction", o.missing_fraction},
                      {"missing_patches", o.missing_patches},
                      {"missing_depth_mm", o.missing_depth_mm},
                      {"holes", o.holes},
                      {"hole_radius_mm", o.hole_radius_mm},
                      {"rotation_deg", vector_json(o.rotation_deg)},
                      {"translation_mm", vector_json(o.translation_mm)},
                      {"field_mm", o.field_mm},
                      {"field_wavelength_mm", o.field_wavelength_mm},
                      {"scan_flank", o.scan_flank},
                      {"stray_fraction", o.stray_fraction},
                      {"stripe_spacing_mm", o.stripe_spacing_mm},
                      {"stripe_angle_deg", o.stripe_angle_deg},
                      {"seed", o.seed}};
  if (o.shape == PanelShape::kPlate) {
    j["plate"] = {{"radius_x_mm", o.plate_radius_x_mm},
                  {"radius_y_mm", o.plate_radius_y_mm},
                  {"porthole_width_mm", o.porthole_width_mm},
                  {"opening", to_string(o.opening)},
                  {"corner_radius_mm", o.corner_radius_mm},
                  {"porthole_height_mm", o.round ? o.porthole_width_mm : o.porthole_height_mm},
                  {"round", o.round},
                  {"porthole_centre_mm", {o.porthole_x_mm, o.porthole_y_mm}},
                  {"clamp_span_mm", o.clamp_span_mm},
                  {"sag_mm", o.sag_mm},
                  {"bend_mm", o.bend_mm},
                  {"twist_mm", o.twist_mm},
                  {"dent_depth_mm", o.dent_depth_mm},
                  {"dent_width_mm", o.dent_width_mm},
                  {"dent_at", o.dent_at}};
  } else {
    j["nosecone"] = {{"barrel_radius_mm", o.barrel_radius_mm},
                     {"window_height_mm", o.window_height_mm},
                     {"window_bottom_mm", o.window_bottom_mm},
                     {"window_top_mm", o.window_top_mm},
                     {"corner_radius_mm", o.corner_radius_mm},
                     {"barrel_length_mm", o.barrel_length_mm},
                     {"ovality_mm", o.ovality_mm},
                     {"droop_mm", o.droop_mm},
                     {"dent_depth_mm", o.dent_depth_mm},
                     {"dent_width_mm", o.dent_width_mm},
                     {"dent_at", o.dent_at}};
  }
  return j;
}

void write_path(const std::string& path, const PanelPath& p) {
  CsvWriter writer({"x_mm", "y_mm", "z_mm", "nx", "ny", "nz"}, 6);
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    for (int k = 0; k < 3; ++k) writer.cell(p.points[i](k));
    for (int k = 0; k < 3; ++k) writer.cell(p.normals[i](k));
    writer.end_row();
  }
  writer.write(path);
}

void write_contour(const std::string& path, const Polyline& c) {
  CsvWriter writer({"x_mm", "y_mm", "z_mm"}, 6);
  for (const Eigen::Vector3d& p : c.points) {
    for (int k = 0; k < 3; ++k) writer.cell(p(k));
    writer.end_row();
  }
  writer.write(path);
}

}  // namespace

bool GeneratePanelOptions::IsValid(std::string* error) const {
  std::string why;
  if (out_path.empty())
    why = "no output path: give the scan file to write (.ply)";
  else if (file_extension(out_path) != ".ply")
    why = out_path + ": the scan is written as .ply";
  else if (!panel.IsValid(&why))
    why = "panel options: " + why;
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

GeneratePanelFiles panel_files(const std::string& scan_path) {
  const std::filesystem::path p(scan_path);
  const auto sibling = [&](const char* suffix) { return std::filesystem::path(p).replace_extension(suffix).string(); };
  return {scan_path,
          sibling(".nominal.ply"),
          sibling(".contour.csv"),
          sibling(".trajectory.csv"),
          sibling(".truth.csv"),
          sibling(".truth.json")};
}

GeneratePanelResult run_generate_panel(const GeneratePanelOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  const PanelData panel = generate_panel(options.panel);
  GeneratePanelResult r;
  r.files = panel_files(options.out_path);
  r.scan_points = panel.scan.size();
  r.contour_points = panel.contour.points.size();
  r.trajectory_rows = panel.trajectory.points.size();
  r.surface_vertices = panel.surface.vertices.size();
  r.surface_faces = panel.surface.faces.size();
  r.perimeter_mm = panel.perimeter_mm;
  r.truth = {{"generator", std::string("generate ") + to_string(options.panel.shape)},
             {"options", options_json(options.panel)}};
  const Eigen::Isometry3d G = panel_rigid_motion(options.panel);
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 4; ++i) rows.push_back({G(i, 0), G(i, 1), G(i, 2), G(i, 3)});
  r.truth["T_deformed_nominal_rigid_part"] = rows;
  nlohmann::json arcs = nlohmann::json::array();
  for (const auto& [start, length] : panel.missing_arcs)
    arcs.push_back({{"start_tau_mm", start}, {"length_tau_mm", length}});
  r.truth["missing_arcs"] = arcs;
  r.truth["counts"] = {{"scan_points", r.scan_points},           {"scan_points_removed", panel.scan_points_removed},
                       {"contour_points", r.contour_points},     {"trajectory_rows", r.trajectory_rows},
                       {"surface_vertices", r.surface_vertices}, {"surface_faces", r.surface_faces}};
  r.truth["perimeter_mm"] = panel.perimeter_mm;
  const auto name = [](const std::string& path) { return std::filesystem::path(path).filename().string(); };
  r.truth["files"] = {{"scan", name(r.files.scan)},
                      {"nominal", name(r.files.nominal)},
                      {"contour", name(r.files.contour)},
                      {"trajectory", name(r.files.trajectory)},
                      {"truth_trajectory", name(r.files.truth_trajectory)}};

  report(options.panel.progress, "write", 0.0);
  OutputSet outputs;  // no half a data set: all six files or none
  write_cloud(r.files.scan, panel.scan);
  write_mesh(r.files.nominal, panel.surface);
  write_contour(r.files.contour, panel.contour);
  write_path(r.files.trajectory, panel.trajectory);
  write_path(r.files.truth_trajectory, panel.truth);
  write_file_atomically(r.files.truth_json, r.truth.dump(2) + "\n");
  outputs.commit();
  report(options.panel.progress, "write", 1.0);
  return r;
}

}  // namespace conform
