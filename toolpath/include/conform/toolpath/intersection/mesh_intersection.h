#pragma once
// The intersection of two triangle meshes given in the same frame (for a tube joint: the leg's outer surface, mesh A,
// and the stub's inner surface, mesh B, both in the stub frame S). A uniform grid over B's triangles (restricted to
// the box both meshes share) finds candidate pairs; each pair is intersected exactly (triangle_triangle.h). The
// result is a soup of segments whose ends are named by (mesh edge, crossed triangle), ready to weld into a graph
// (intersection_graph.h). Parallel over A's triangles with OpenMP; the segments are sorted by (face of A, face of B),
// so the output is the same for any number of threads.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "conform/core/mesh.h"
#include "conform/toolpath/intersection/triangle_triangle.h"

namespace conform {

struct MeshIntersectionOptions {
  double cell_mm = 0.0;              // grid cell edge, mm; 0: 1.5 x the mean extent of B's triangles
  std::int64_t max_cells = 1 << 23;  // the cell edge grows until the grid has at most this many cells

  bool IsValid(std::string* error) const;
};

struct IntersectionSegment {
  std::int32_t face_a = 0;
  std::int32_t face_b = 0;
  EdgeCrossing ends[2];
};

struct MeshIntersectionResult {
  std::vector<IntersectionSegment> segments;  // sorted by (face_a, face_b)
  std::size_t candidate_pairs = 0;            // triangle pairs whose boxes overlap
  // Pairs whose exact intersection had a crossing count other than 0 or 2 (only degenerate, zero-area triangles do);
  // those pairs give no segment, and the graph check then names where the curve is broken.
  std::size_t odd_pairs = 0;
  double cell_mm = 0.0;  // the grid cell used
};

// Throws conform::Error when the options are invalid or a mesh has no faces or a non-finite vertex.
MeshIntersectionResult intersect_meshes(const Mesh& a, const Mesh& b, const MeshIntersectionOptions& options = {});

}  // namespace conform
