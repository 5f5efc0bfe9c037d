#include "conform/core/mesh_weld.h"

#include "vertex_welder.h"

namespace conform {

MeshWeldResult weld_coincident_vertices(const Mesh& mesh, const std::string& what) {
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
  for (const Face& f : mesh.faces) {
    const Face g = {index[static_cast<std::size_t>(f[0])], index[static_cast<std::size_t>(f[1])],
                    index[static_cast<std::size_t>(f[2])]};
    if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) {
      ++result.dropped_faces;
      continue;
    }
    result.mesh.faces.push_back(g);
  }
  return result;
}

}  // namespace conform
