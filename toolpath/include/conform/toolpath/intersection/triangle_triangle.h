#pragma once
// Exact intersection of a triangle of mesh A (the leg) with a triangle of mesh B (the stub), as the mesh intersection
// needs it: the intersection segment's two ends, each named by the mesh edge and the triangle it crosses, so that
// segments from neighbouring triangle pairs weld by name, never by comparing coordinates.
//
// Degenerate contact (a vertex on the other triangle's plane, an edge through the other's edge) is resolved by a
// symbolic perturbation: mesh B is displaced by t = eps w1 + eps^2 w2 (eps -> 0, fixed generic w1, w2), and every
// decision is the exact sign of the perturbed determinant, expanded in eps (simulation of simplicity, Edelsbrunner &
// Muecke 1990). Each decision is then consistent across all triangles sharing an edge, so the welded segments form
// closed curves even when vertices of one mesh lie exactly on the other. Only a degenerate (zero-area) triangle or
// a zero-length edge can give "no decision" (sign 0); it is treated as not crossing.

#include <cstdint>

#include <Eigen/Core>

namespace conform {

// Which mesh an edge belongs to.
enum class MeshSide : std::uint8_t { kA = 0, kB = 1 };

// Where an edge of one mesh crosses a triangle of the other: the intersection curve's vertex.
struct EdgeCrossing {
  MeshSide edge_mesh = MeshSide::kA;
  std::int32_t v0 = 0;  // the edge's vertex indices in its mesh, v0 < v1
  std::int32_t v1 = 0;
  std::int32_t triangle = 0;  // the crossed triangle's index in the other mesh
  Eigen::Vector3d point = Eigen::Vector3d::Zero();

  bool same_key(const EdgeCrossing& o) const {
    return edge_mesh == o.edge_mesh && v0 == o.v0 && v1 == o.v1 && triangle == o.triangle;
  }
  bool key_less(const EdgeCrossing& o) const;
};

// A triangle given by its three vertex positions and indices (in its own mesh).
struct IndexedTriangle {
  Eigen::Vector3d p[3];
  std::int32_t index[3] = {0, 0, 0};
  std::int32_t face = 0;
};

// Perturbed sign of orient3d(b0, b1, b2, a) for a point a of mesh A against a triangle of B (B displaced by t).
int side_of_a_point(const IndexedTriangle& b, const Eigen::Vector3d& a);
// Perturbed sign of orient3d(a0, a1, a2, b) for a point b of B (displaced by t) against a triangle of A.
int side_of_b_point(const IndexedTriangle& a, const Eigen::Vector3d& b);

// Whether the edge (p, q) of mesh `edge_mesh` crosses triangle `tri` of the other mesh (perturbed, exact). When it
// does, *point is where (the line p q meets the triangle's plane, rounded).
bool edge_crosses_triangle(MeshSide edge_mesh, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                           const IndexedTriangle& tri, Eigen::Vector3d* point);

// The intersection of triangle a (mesh A) and triangle b (mesh B): 0 crossings (disjoint) or 2 (a segment). Returns
// the count; the ends in ends[0], ends[1] (in the order found: edges of a, then edges of b). A count other than
// 0 or 2 can only come from degenerate triangles.
int intersect_triangles(const IndexedTriangle& a, const IndexedTriangle& b, EdgeCrossing ends[6]);

}  // namespace conform
