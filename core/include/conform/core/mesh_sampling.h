#pragma once
// Points spread over a triangle mesh's surface in proportion to the triangles' areas, for jobs that need the surface
// rather than the vertices: a CAD tessellation's vertices lie on its faces' boundaries only (a cylinder's on its two
// rims), which says nothing about the surface between them.
//
//   const PhongSurface smooth(mesh);
//   const MeshSurfaceSample s = sample_mesh_surface(mesh, 20000, &smooth);   // on the smooth surface, with normals

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/core/phong_surface.h"

namespace conform {

struct MeshSurfaceSample {
  std::vector<Eigen::Vector3d> points;   // mm
  std::vector<Eigen::Vector3d> normals;  // unit: the face's (flat) or the smooth surface's; as the faces are wound
  std::vector<std::int32_t> faces;       // the face each point was taken from
};

// `count` points over the mesh's faces, each face receiving a share proportional to its area: the k-th point from
// the k-th term of a three-dimensional Kronecker sequence (Roberts' R3, the generalised golden ratio), the first
// coordinate choosing the face through the cumulative areas and the other two the place in it (uniform by area).
// Deterministic without a seed, and evenly spread (a low-discrepancy sequence: no clusters, no gaps a random draw
// would leave). smooth: a PhongSurface over the same mesh to move each point onto the smooth surface (the points of a
// curved CAD face then lie on that face, not on its chords); nullptr: on the flat triangles. Faces without area get
// none. Throws conform::Error for a mesh without faces of positive area, a face index out of range, or count 0.
MeshSurfaceSample sample_mesh_surface(const Mesh& mesh, std::size_t count, const PhongSurface* smooth = nullptr);

}  // namespace conform
