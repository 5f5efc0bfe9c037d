#include "conform/core/mesh.h"

#include <string>

#include "conform/core/error.h"

namespace conform {

void check_consistent(const Cloud& cloud, const char* what) {
  if (cloud.has_normals() && cloud.normals.size() != cloud.points.size()) {
    throw Error(std::string(what) + ": " + std::to_string(cloud.normals.size()) + " normals for " +
                std::to_string(cloud.points.size()) + " points");
  }
}

void check_consistent(const Mesh& mesh, const char* what) {
  if (mesh.has_normals() && mesh.normals.size() != mesh.vertices.size()) {
    throw Error(std::string(what) + ": " + std::to_string(mesh.normals.size()) + " normals for " +
                std::to_string(mesh.vertices.size()) + " vertices");
  }
  const auto n = static_cast<std::int64_t>(mesh.vertices.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (std::int32_t v : mesh.faces[f]) {
      if (v < 0 || v >= n) {
        throw Error(std::string(what) + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(v) +
                    " of " + std::to_string(n));
      }
    }
  }
}

namespace {
Eigen::Vector3d face_cross(const Mesh& mesh, std::size_t f) {
  const Face& t = mesh.faces[f];
  const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
  const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
  const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
  return (b - a).cross(c - a);
}
}  // namespace

Eigen::Vector3d face_normal(const Mesh& mesh, std::size_t f) {
  const Eigen::Vector3d n = face_cross(mesh, f);
  const double len = n.norm();
  return len > 0.0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

VertexFaces faces_around_vertices(const Mesh& mesh) {
  const std::size_t n = mesh.vertices.size();
  VertexFaces out;
  out.start.assign(n + 1, 0);
  for (const Face& face : mesh.faces) {
    for (std::int32_t i : face) ++out.start[static_cast<std::size_t>(i) + 1];
  }
  for (std::size_t v = 0; v < n; ++v) out.start[v + 1] += out.start[v];
  out.faces.resize(out.start[n]);
  std::vector<std::size_t> fill(out.start.begin(), out.start.end() - 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (std::int32_t i : mesh.faces[f]) out.faces[fill[static_cast<std::size_t>(i)]++] = f;
  }
  return out;
}

double face_area(const Mesh& mesh, std::size_t f) { return 0.5 * face_cross(mesh, f).norm(); }

double surface_area(const Mesh& mesh) {
  double area = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) area += face_area(mesh, f);
  return area;
}

std::vector<Eigen::Vector3d> vertex_normals_from_faces(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> normals(mesh.vertices.size(), Eigen::Vector3d::Zero());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    // The cross product's length is twice the area: summing it weights each face by its area.
    const Eigen::Vector3d n = face_cross(mesh, f);
    for (std::int32_t v : mesh.faces[f]) normals[static_cast<std::size_t>(v)] += n;
  }
  for (Eigen::Vector3d& n : normals) {
    const double len = n.norm();
    if (len > 0.0) n /= len;
  }
  return normals;
}

Cloud to_cloud(const Mesh& mesh) {
  Cloud cloud;
  cloud.points.resize(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3f p = mesh.vertices[i].cast<float>();
    cloud.points[i] = pcl::PointXYZ(p.x(), p.y(), p.z());
  }
  if (mesh.has_normals()) {
    cloud.normals.resize(mesh.normals.size());
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
      const Eigen::Vector3f n = mesh.normals[i].cast<float>();
      cloud.normals[i] = pcl::Normal(n.x(), n.y(), n.z());
    }
  }
  return cloud;
}

Mesh to_mesh(const Cloud& cloud) {
  Mesh mesh;
  mesh.vertices.reserve(cloud.size());
  for (const pcl::PointXYZ& p : cloud.points) mesh.vertices.push_back(p.getVector3fMap().cast<double>());
  mesh.normals.reserve(cloud.normals.size());
  for (const pcl::Normal& n : cloud.normals) mesh.normals.push_back(n.getNormalVector3fMap().cast<double>());
  return mesh;
}

}  // namespace conform
