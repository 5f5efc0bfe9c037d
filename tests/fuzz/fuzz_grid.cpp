// libFuzzer harness: the surface grids of weld-layers (a CSV table of row,col,x_mm,y_mm,z_mm -> SurfaceGrid)
// (tests/fuzz/README.md).
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/fitting/surface_grid.h"
#include "fuzz_input.h"

CONFORM_FUZZ_READER(".csv", conform::surface_grid_from_table(conform::read_csv(path)))
