#include "conform/core/mesh_boundary.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "conform/core/geometry.h"

namespace conform {
namespace {

using Edge = std::pair<int, int>;  // directed, as a face winds

// Boundary edges in face winding direction, sorted by (from, to) so every walk below is deterministic.
std::vector<Edge> boundary_edges(const Mesh& mesh) {
  std::map<Edge, std::pair<int, Edge>> uses;  // undirected key -> (count, first directed edge)
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const Edge directed{f[static_cast<std::size_t>(k)], f[static_cast<std::size_t>((k + 1) % 3)]};
      if (directed.first == directed.second) continue;  // a collapsed face's zero-length edge bounds nothing
      const Edge key{std::min(directed.first, directed.second), std::max(directed.first, directed.second)};
      auto [it, inserted] = uses.try_emplace(key, 0, directed);
      ++it->second.first;
    }
  }
  std::vector<Edge> edges;
  for (const auto& [key, use] : uses) {
    if (use.first == 1) edges.push_back(use.second);
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

class BoundaryWalker {
 public:
  explicit BoundaryWalker(const std::vector<Edge>& edges) : edges_(edges), used_(edges.size(), false) {
    for (std::size_t e = 0; e < edges.size(); ++e) {
      out_[edges[e].first].push_back(e);
      ++in_degree_[edges[e].second];
    }
  }

  std::vector<std::pair<std::vector<int>, bool>> walk() {
    std::vector<std::pair<std::vector<int>, bool>> result;
    // Chains first, from every vertex where the boundary branches or ends, so that each chain is maximal.
    for (const auto& [vertex, outgoing] : out_) {
      if (regular(vertex)) continue;
      for (std::size_t e : outgoing) {
        if (!used_[e]) result.emplace_back(follow(e), false);
      }
    }
    // What is left are simple cycles; start each at its lowest vertex (edges are sorted by their start).
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      if (used_[e]) continue;
      std::vector<int> loop = follow(e);
      loop.pop_back();  // the walk came back to its start
      result.emplace_back(std::move(loop), true);
    }
    std::stable_sort(result.begin(), result.end(),
                     [](const auto& a, const auto& b) { return a.first.front() < b.first.front(); });
    return result;
  }

 private:
  bool regular(int vertex) const {
    const auto in = in_degree_.find(vertex);
    const auto out = out_.find(vertex);
    return in != in_degree_.end() && in->second == 1 && out != out_.end() && out->second.size() == 1;
  }

  // Walks from edge e until the boundary branches, ends, or closes; returns the vertices visited.
  std::vector<int> follow(std::size_t e) {
    std::vector<int> vertices{edges_[e].first};
    const int start = edges_[e].first;
    while (true) {
      used_[e] = true;
      const int to = edges_[e].second;
      vertices.push_back(to);
      if (to == start || !regular(to)) break;
      e = out_[to].front();
      if (used_[e]) break;
    }
    return vertices;
  }

  const std::vector<Edge>& edges_;
  std::vector<bool> used_;
  std::map<int, std::vector<std::size_t>> out_;
  std::map<int, int> in_degree_;
};

// Every boundary walk of the mesh: vertex indices and whether the walk closed.
std::vector<std::pair<std::vector<int>, bool>> walk_boundary(const Mesh& mesh) {
  check_consistent(mesh, "mesh boundary");
  if (count_non_finite(mesh) > 0) throw Error("mesh boundary: the mesh has a vertex with a NaN or infinite coordinate");
  const std::vector<Edge> edges = boundary_edges(mesh);
  return BoundaryWalker(edges).walk();
}

}  // namespace

std::vector<std::vector<int>> boundary_loops(const Mesh& mesh) {
  std::vector<std::vector<int>> loops;
  for (auto& [vertices, closed] : walk_boundary(mesh)) loops.push_back(std::move(vertices));
  return loops;
}

std::vector<Polyline> boundary_polylines(const Mesh& mesh) {
  std::vector<Polyline> polylines;
  for (const auto& [vertices, closed] : walk_boundary(mesh)) {
    Polyline p;
    p.closed = closed;
    for (int v : vertices) p.points.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
    polylines.push_back(std::move(p));
  }
  return polylines;
}

}  // namespace conform
