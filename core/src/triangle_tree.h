#pragma once
// What conform::TriangleIndex holds (core/src/triangle_index.cpp queries it): a bounding-volume hierarchy over the
// mesh's triangles and the pseudo-normals for signs.
//
// The tree is binary; an inner node stores the boxes of both its children, so that a query reads one 64-byte node
// to decide which child to visit first. Boxes are float, rounded outwards and padded, so that they are never
// closer to a query than the double-precision closest point they hold (see triangle_tree_build.cpp).

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform::detail {

struct TriangleTree {
  struct alignas(64) Node {
    float lo[2][3];         // lower corner of child 0 and child 1
    float hi[2][3];         // upper corner
    std::int32_t ref[2];    // an inner child: its node index; a leaf: its first triangle
    std::int32_t count[2];  // 0 for an inner child; a leaf's triangle count (triangles[ref, ref + count))
  };
  struct Triangle {
    Eigen::Vector3d a, b, c;  // the face's vertices in the face's own order
    std::int32_t face = 0;
  };

  // The root: a leaf (root_count > 0, the mesh has few faces) or nodes[0].
  Eigen::Vector3d root_lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d root_hi = Eigen::Vector3d::Zero();
  std::int32_t root_count = 0;
  std::vector<Node> nodes;          // depth first
  std::vector<Triangle> triangles;  // in leaf order

  std::vector<Face> faces;
  // The pseudo-normals (build_pseudo_normals), made on the first TriangleIndex::normal_at.
  std::vector<Eigen::Vector3d> face_normals;    // unit, zero for a face without area
  std::vector<Eigen::Vector3d> edge_normals;    // 3 per face (edges 01, 12, 20), unit or zero
  std::vector<Eigen::Vector3d> vertex_normals;  // per mesh vertex, unit or zero
};

// Longest path from the root to a leaf that build_tree makes (median splits: about log2(faces / 4)); a query's
// explicit stack holds at most this many entries.
inline constexpr int kMaxTreeDepth = 96;

// nodes, triangles and the root from the mesh's faces (checked: indices in range, vertices finite).
void build_tree(const Mesh& mesh, TriangleTree& tree);
// face_normals, edge_normals and vertex_normals of `mesh` (whose faces are tree.faces).
void build_pseudo_normals(const Mesh& mesh, TriangleTree& tree);

}  // namespace conform::detail
