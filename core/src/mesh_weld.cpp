#include "conform/core/mesh_weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>

#include "vertex_welder.h"

namespace conform {

MeshWeldResult weld_coincident_vertices(const Mesh& mesh, const std::string& what,
                                        std::vector<std::size_t>* kept_faces) {
  check_consistent(mesh, what.c_str());
  detail::VertexWelder welder(what, mesh.vertices.size());
  std::vector<std::int32_t> index(mesh.vertices.size());
  MeshWeldResult result;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices[i];
    const std::size_t before = welder.size();
    index[i] = welder.add(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
    if (welder.size() > before) {
      result.mesh.vertices.push_back(p);
      if (mesh.has_normals()) result.mesh.normals.push_back(mesh.normals[i]);
    }
  }
  result.merged_vertices = mesh.vertices.size() - result.mesh.vertices.size();
  result.mesh.faces.reserve(mesh.faces.size());
  if (kept_faces != nullptr) kept_faces->clear();
  for (std::size_t i = 0; i < mesh.faces.size(); ++i) {
    const Face& f = mesh.faces[i];
    const Face g = {index[static_cast<std::size_t>(f[0])], index[static_cast<std::size_t>(f[1])],
                    index[static_cast<std::size_t>(f[2])]};
    if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) {
      ++result.dropped_faces;
      continue;
    }
    result.mesh.faces.push_back(g);
    if (kept_faces != nullptr) kept_faces->push_back(i);
  }
  return result;
}

double median_edge_length(const Mesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(3 * mesh.faces.size());
  for (const Face& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      lengths.push_back(
          (mesh.vertices[static_cast<std::size_t>(f[k])] - mesh.vertices[static_cast<std::size_t>(f[(k + 1) % 3])])
              .norm());
    }
  }
  if (lengths.empty()) return 0.0;
  const auto mid = lengths.begin() + static_cast<long>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  return *mid;
}

MeshWeldResult weld_near_vertices(const Mesh& mesh, double tolerance_mm, const std::string& what) {
  MeshWeldResult exact = weld_coincident_vertices(mesh, what);
  if (!(tolerance_mm > 0.0) || !std::isfinite(tolerance_mm)) return exact;
  const Mesh& m = exact.mesh;
  // Cells of the tolerance's size: a vertex's partners lie in its cell or the 26 around it.
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const {
      return static_cast<std::size_t>(c[0] * 73856093LL ^ c[1] * 19349663LL ^ c[2] * 83492791LL);
    }
  };
  auto cell_of = [&](const Eigen::Vector3d& p) {
    return Cell{static_cast<std::int64_t>(std::floor(p.x() / tolerance_mm)),
                static_cast<std::int64_t>(std::floor(p.y() / tolerance_mm)),
                static_cast<std::int64_t>(std::floor(p.z() / tolerance_mm))};
  };
  std::unordered_map<Cell, std::vector<std::int32_t>, CellHash> kept_in;
  std::vector<std::int32_t> index(m.vertices.size());
  MeshWeldResult result;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Eigen::Vector3d& p = m.vertices[i];
    const Cell c = cell_of(p);
    std::int32_t best = -1;
    double best_distance = tolerance_mm;
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = kept_in.find(Cell{c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == kept_in.end()) continue;
          for (const std::int32_t k : it->second) {
            const double d = (result.mesh.vertices[static_cast<std::size_t>(k)] - p).norm();
            if (d < best_distance || (d == best_distance && best >= 0 && k < best)) best = k, best_distance = d;
          }
        }
      }
    }
    if (best < 0) {
      best = static_cast<std::int32_t>(result.mesh.vertices.size());
      result.mesh.vertices.push_back(p);
      if (m.has_normals()) result.mesh.normals.push_back(m.normals[i]);
      kept_in[c].push_back(best);
    }
    index[i] = best;
  }
  result.merged_vertices = exact.merged_vertices + (m.vertices.size() - result.mesh.vertices.size());
  result.dropped_faces = exact.dropped_faces;
  std::set<std::array<std::int32_t, 3>> seen;
  for (const Face& f : m.faces) {
    const Face g = {index[static_cast<std::size_t>(f[0])], index[static_cast<std::size_t>(f[1])],
                    index[static_cast<std::size_t>(f[2])]};
    std::array<std::int32_t, 3> key = {g[0], g[1], g[2]};
    std::sort(key.begin(), key.end());
    const bool duplicate = !seen.insert(key).second && g != f;  // a face the welding made a copy of another
    if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2] || duplicate) {
      ++result.dropped_faces;
      continue;
    }
    result.mesh.faces.push_back(g);
  }
  return result;
}

}  // namespace conform
