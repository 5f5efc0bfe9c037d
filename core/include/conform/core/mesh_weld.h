#pragma once
// Welding a triangle soup: vertices at the same position (after rounding to float, the precision scanners and STL
// write; 6e-5 mm at 1 m) become one shared vertex, so that neighbouring faces share their edges. A PLY written as a
// triangle soup, or a scan with duplicated seam vertices, then has the same topology as the STL of the same surface
// (whose reader welds the same way, core/src/vertex_welder.h). Faces that collapse (two corners welded) are dropped.

#include <cstddef>
#include <string>
#include <vector>

#include "conform/core/mesh.h"

namespace conform {

struct MeshWeldResult {
  Mesh mesh;                        // the welded mesh: the first vertex of each group keeps its double position
  std::size_t merged_vertices = 0;  // vertices removed (welded into an earlier one)
  std::size_t dropped_faces = 0;    // faces that collapsed
};

// `what` names the mesh in errors. Normals, if any, are those of the kept vertices. Unchanged (merged_vertices == 0)
// for a mesh without coincident vertices. Throws conform::Error for an inconsistent mesh. `kept_faces` (when not null)
// receives, per face of the welded mesh, the index of the input face it is (faces keep their order).
MeshWeldResult weld_coincident_vertices(const Mesh& mesh, const std::string& what,
                                        std::vector<std::size_t>* kept_faces = nullptr);

// The median length of the mesh's edges (each face's three, shared edges counted per face), mm; 0 without faces.
double median_edge_length(const Mesh& mesh);

// Welds vertices closer than `tolerance_mm` (an unwelded scanner mesh: a seam's vertices duplicated a few microns
// apart). Vertices are taken in index order; each joins the nearest earlier kept vertex within the tolerance (no
// chains: a kept vertex never moves), else it is kept. Faces that collapse are dropped, as are faces that become
// duplicates of an earlier face. tolerance_mm <= 0: as weld_coincident_vertices. Same mesh, same result.
MeshWeldResult weld_near_vertices(const Mesh& mesh, double tolerance_mm, const std::string& what);

}  // namespace conform
