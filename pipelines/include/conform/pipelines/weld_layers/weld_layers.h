#pragma once
// `conform weld-layers`: reads the eroded and the reference grid files (CSV row,col,x_mm,y_mm,z_mm, full rectangular
// grids; without a reference file the reference is rebuilt as the Coons patch of the eroded grid's border, which
// needs the damage to stay clear of the border), fits C2 Bézier networks through them, plans the weld layers (toolpath/weld/weld_layers.h) and writes the paths
// as CSV layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz.

#include <string>

#include "conform/fitting/surface_grid.h"
#include "conform/toolpath/weld/weld_layers.h"

namespace conform {

// Per grid (the Bézier network keeps ~400 bytes a node): a larger grid is refused before it is fitted (exit 2).
constexpr long kMaxWeldGridNodes = 1100000;

struct WeldLayersJobOptions {
  std::string eroded_path;     // eroded grid CSV
  std::string reference_path;  // reference grid CSV; empty: the Coons patch of the eroded grid's border
  WeldLayerOptions weld;
  std::string out_path;        // CSV to write, whole or not at all; empty: write nothing
  bool keep_geometry = false;    // keep the eroded grid in the result (for a report)
};

struct WeldLayersJobResult {
  WeldLayerResult weld;
  int eroded_rows = 0, eroded_cols = 0;
  int reference_rows = 0, reference_cols = 0;
  std::string out_path;  // the file written; empty when none was asked for or the plan did not succeed
  SurfaceGrid eroded;    // with keep_geometry (else empty), as read (pipelines/weld_layers/weld_layers_report.h)
};

// Throws conform::Error naming the file and row (a hole, a ragged row, a bad number) or the bad option. A run that
// finds no damage returns weld.ok = false and writes nothing.
WeldLayersJobResult run_weld_layers(const WeldLayersJobOptions& options);

// The CSV text: header layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz; 6 decimals for mm, 9 for the normals.
std::string weld_layers_csv(const WeldLayerResult& result);

}  // namespace conform
