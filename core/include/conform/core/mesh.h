#pragma once
// A triangle mesh in millimetres. Vertices are double so that generated ground truth is exact;
// faces wind counter-clockwise seen from the side the surface normal points to.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cloud.h"

namespace conform {

using Face = std::array<std::int32_t, 3>;

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;  // mm
  std::vector<Eigen::Vector3d> normals;   // empty, or one unit normal per vertex
  std::vector<Face> faces;                // empty for a point cloud read as a mesh

  bool has_normals() const { return !normals.empty(); }
  bool has_faces() const { return !faces.empty(); }
};

// Throws conform::Error (naming `what`) when a face index is out of range or normals are not one per vertex.
void check_consistent(const Mesh& mesh, const char* what);

// Unit normal of face f by the right-hand rule; zero for a degenerate (zero-area) face.
Eigen::Vector3d face_normal(const Mesh& mesh, std::size_t f);
double face_area(const Mesh& mesh, std::size_t f);
double surface_area(const Mesh& mesh);

// Per-vertex unit normals: the area-weighted mean of the adjacent faces' normals (zero for isolated vertices).
std::vector<Eigen::Vector3d> vertex_normals_from_faces(const Mesh& mesh);

// The faces around each vertex, in compressed rows: those of vertex v are faces[start[v]] .. faces[start[v + 1] - 1],
// ascending. The faces' indices must be in range (check_consistent).
struct VertexFaces {
  std::vector<std::size_t> start;  // vertices + 1 entries
  std::vector<std::size_t> faces;
};
VertexFaces faces_around_vertices(const Mesh& mesh);

// The mesh's vertices (and their normals, if any) as a float cloud.
Cloud to_cloud(const Mesh& mesh);
// A cloud as a mesh without faces (vertices in double).
Mesh to_mesh(const Cloud& cloud);

}  // namespace conform
