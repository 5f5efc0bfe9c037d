#pragma once
// `conform generate plate` and `conform generate nosecone`: a deformed panel with an opening (datasets/panel.h)
// written as files for `conform sicp`, beside the scan named by out_path (foo.ply):
//   foo.ply              the scan of the deformed part (points, binary PLY)
//   foo.nominal.ply      the nominal surface around the opening, with the opening's flank (mesh)
//   foo.contour.csv      the nominal contour, x_mm,y_mm,z_mm, ordered, closed
//   foo.trajectory.csv   the nominal deburring trajectory, x_mm,y_mm,z_mm,nx,ny,nz
//   foo.truth.csv        the same trajectory on the deformed part (ground truth), same rows
//   foo.truth.json       every parameter, the seed, the rigid part of the deformation, the missing arcs, counts
// All appear, or none does; the same options give the same bytes.

#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include "conform/datasets/panel.h"
#include "conform/datasets/panel_shape.h"

namespace conform {

struct GeneratePanelOptions {
  PanelOptions panel;    // its progress callback reports the generation
  std::string out_path;  // the scan, .ply

  bool IsValid(std::string* error) const;
};

struct GeneratePanelFiles {
  std::string scan, nominal, contour, trajectory, truth_trajectory, truth_json;
};

struct GeneratePanelResult {
  GeneratePanelFiles files;
  std::size_t scan_points = 0;
  std::size_t contour_points = 0;
  std::size_t trajectory_rows = 0;
  std::size_t surface_vertices = 0;
  std::size_t surface_faces = 0;
  double perimeter_mm = 0.0;
  nlohmann::json truth;  // what files.truth_json holds
};

// foo.ply -> foo.nominal.ply, foo.contour.csv, ...
GeneratePanelFiles panel_files(const std::string& scan_path);

// Throws conform::Error naming the option or the file; a failure leaves none of the files behind.
GeneratePanelResult run_generate_panel(const GeneratePanelOptions& options);

}  // namespace conform
