#pragma once
// `conform info`: what a file holds, read the way every job reads it, before any job runs.

#include <cstddef>
#include <string>
#include <vector>

#include "conform/core/cad.h"
#include "conform/core/geometry.h"

namespace conform {

struct InfoOptions {
  std::string path;
  double mm_per_unit = 1.0;  // millimetres per unit of a mesh or cloud file (1000 for metres); a CAD file says its own
  CadReadOptions cad;        // a CAD file: the tessellation it would be read with
};

struct InfoResult {
  std::string path;
  std::string format;      // the extension it was read as, e.g. ".ply"
  std::size_t points = 0;  // vertices of a mesh, points of a cloud
  std::size_t faces = 0;   // triangles (polygons counted after fan triangulation)
  bool has_normals = false;
  std::size_t non_finite = 0;  // points with a NaN or infinite coordinate
  BoundingBox box;             // over the finite points, mm
  double surface_area_mm2 = 0.0;
  std::vector<std::string> warnings;
  CadReport cad;  // cad.read: a CAD file (units, bodies, the tessellation used)

  // A file conform can use as it is: points present, all finite.
  bool usable() const { return points > 0 && non_finite == 0; }
};

// Throws conform::Error naming the file when it cannot be read at all.
InfoResult run_info(const InfoOptions& options);

}  // namespace conform
