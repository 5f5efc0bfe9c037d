// The angle-weighted pseudo-normals that give a closest point on an edge or a vertex its side of the surface
// (Baerentzen & Aanaes, "Signed distance computation using the angle weighted pseudonormal", IEEE TVCG 11(3), 2005):
// for a closed, consistently wound mesh, sign(dot(p - c, n_c)) is the side of p, whichever feature c lies on.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "triangle_tree.h"

namespace conform::detail {
namespace {

Eigen::Vector3d unit_or_zero(const Eigen::Vector3d& v) {
  const double len = v.norm();
  return len > 0.0 ? Eigen::Vector3d(v / len) : Eigen::Vector3d::Zero();
}

// Edge pseudo-normal: the sum of the normals of the faces sharing the edge, each weighted by its angle about the
// edge, pi (Baerentzen & Aanaes 2005, Sec. 3), i.e. their plain sum; a boundary edge has its one face's normal.
void edge_normals(TriangleTree& tree) {
  const std::size_t n = tree.faces.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;  // (undirected edge key, 3 * face + local edge)
  edges.reserve(3 * n);
  for (std::size_t f = 0; f < n; ++f) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto u = static_cast<std::uint32_t>(tree.faces[f][k]);
      const auto v = static_cast<std::uint32_t>(tree.faces[f][(k + 1) % 3]);
      const std::uint64_t key = (std::uint64_t{std::min(u, v)} << 32) | std::max(u, v);
      edges.emplace_back(key, static_cast<std::uint32_t>(3 * f + k));
    }
  }
  std::sort(edges.begin(), edges.end());
  tree.edge_normals.assign(3 * n, Eigen::Vector3d::Zero());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (; j < edges.size() && edges[j].first == edges[i].first; ++j) sum += tree.face_normals[edges[j].second / 3];
    const Eigen::Vector3d normal = unit_or_zero(sum);
    for (; i < j; ++i) tree.edge_normals[edges[i].second] = normal;
  }
}

// Vertex pseudo-normal: the sum of the incident faces' normals, each weighted by the face's angle at the vertex
// (Baerentzen & Aanaes 2005, Eq. 1, after Thuermer & Wuethrich 1998).
void vertex_normals(TriangleTree& tree, const Mesh& mesh) {
  tree.vertex_normals.assign(mesh.vertices.size(), Eigen::Vector3d::Zero());
  for (std::size_t f = 0; f < tree.faces.size(); ++f) {
    if (tree.face_normals[f].squaredNorm() == 0.0) continue;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tree.faces[f][k]);
      const Eigen::Vector3d& p = mesh.vertices[v];
      const Eigen::Vector3d e1 = mesh.vertices[static_cast<std::size_t>(tree.faces[f][(k + 1) % 3])] - p;
      const Eigen::Vector3d e2 = mesh.vertices[static_cast<std::size_t>(tree.faces[f][(k + 2) % 3])] - p;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      tree.vertex_normals[v] += angle * tree.face_normals[f];
    }
  }
  for (Eigen::Vector3d& n : tree.vertex_normals) n = unit_or_zero(n);
}

}  // namespace

void build_pseudo_normals(const Mesh& mesh, TriangleTree& tree) {
  tree.face_normals.resize(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) tree.face_normals[f] = face_normal(mesh, f);
  edge_normals(tree);
  vertex_normals(tree, mesh);
}

}  // namespace conform::detail
