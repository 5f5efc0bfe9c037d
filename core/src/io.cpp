// Reading and writing by extension, and the NonFinitePolicy; the formats themselves live in one file each
// (ply_*.cpp, stl_*.cpp, obj_io.cpp, point_list_io.cpp, pcd_io.cpp).

#include "conform/core/io.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "conform/core/error.h"
#include "io_formats.h"

namespace conform {

namespace {

enum class Format { kPly, kStl, kObj, kPointList, kPcd, kCad };

constexpr const char* kSupported = ".ply .stl .obj .pcd .xyz .txt .asc .csv; CAD .step .stp .iges .igs";

Format format_of(const std::string& path) {
  const std::string extension = file_extension(path);
  if (extension == ".ply") return Format::kPly;
  if (extension == ".stl") return Format::kStl;
  if (extension == ".obj") return Format::kObj;
  if (extension == ".pcd") return Format::kPcd;
  if (is_cad_file(path)) return Format::kCad;
  if (extension == ".xyz" || extension == ".txt" || extension == ".asc" || extension == ".csv") {
    return Format::kPointList;
  }
  if (extension.empty()) {
    throw Error(path + ": no file extension to tell the format by (supported: " + kSupported + ")");
  }
  throw Error(path + ": unknown file extension '" + extension + "' (supported: " + kSupported + ")");
}

Mesh read_by_format(const std::string& path, const ReadOptions& options, ReadReport& report) {
  switch (format_of(path)) {
    case Format::kPly:
      return detail::read_ply(path, report);
    case Format::kStl:
      return detail::read_stl(path, report);
    case Format::kObj:
      return detail::read_obj(path, report);
    case Format::kPointList:
      return detail::read_point_list(path, report);
    case Format::kPcd:
      return detail::read_pcd(path, report);
    case Format::kCad:
      return read_cad(path, options.cad, &report.cad, &report.warnings);
  }
  throw Error(path + ": unsupported format");
}

bool is_finite(const Eigen::Vector3d& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

// Removes the vertices whose `keep` is false, their normals and every face that uses one of them; the remaining
// faces are re-indexed. Returns how many faces went.
std::size_t remove_vertices(Mesh& mesh, const std::vector<bool>& keep) {
  std::vector<std::int32_t> new_index(mesh.vertices.size(), -1);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!keep[i]) continue;
    new_index[i] = static_cast<std::int32_t>(kept);
    mesh.vertices[kept] = mesh.vertices[i];
    if (mesh.has_normals()) mesh.normals[kept] = mesh.normals[i];
    ++kept;
  }
  mesh.vertices.resize(kept);
  if (mesh.has_normals()) mesh.normals.resize(kept);

  std::size_t kept_faces = 0;
  for (const Face& f : mesh.faces) {
    const Face g = {new_index[static_cast<std::size_t>(f[0])], new_index[static_cast<std::size_t>(f[1])],
                    new_index[static_cast<std::size_t>(f[2])]};
    if (g[0] >= 0 && g[1] >= 0 && g[2] >= 0) mesh.faces[kept_faces++] = g;
  }
  const std::size_t dropped_faces = mesh.faces.size() - kept_faces;
  mesh.faces.resize(kept_faces);
  return dropped_faces;
}

void apply_non_finite_policy(const std::string& path, NonFinitePolicy policy, Mesh& mesh, ReadReport& report) {
  std::size_t count = 0;
  std::size_t first = 0;
  std::vector<bool> keep(mesh.vertices.size(), true);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (is_finite(mesh.vertices[i])) continue;
    if (count++ == 0) first = i;
    keep[i] = false;
  }
  report.non_finite_points = count;
  if (count == 0 || policy == NonFinitePolicy::kKeep) return;
  const std::string which = std::to_string(count) + (count == 1 ? " vertex has" : " vertices have") +
                            " a NaN or infinite coordinate (the first is vertex " + std::to_string(first) + ")";
  if (policy == NonFinitePolicy::kReject) throw Error(path + ": " + which);
  const std::size_t dropped_faces = remove_vertices(mesh, keep);
  std::string warning = path + ": dropped " + std::to_string(count) + (count == 1 ? " vertex" : " vertices") +
                        " with a NaN or infinite coordinate (the first was vertex " + std::to_string(first) + ")";
  if (dropped_faces > 0) warning += " and the " + std::to_string(dropped_faces) + " faces that used them";
  report.warnings.push_back(warning);
}

[[noreturn]] void throw_faces_lost(const std::string& path, const Mesh& mesh) {
  throw Error(path + ": " + file_extension(path) + " files hold points only: writing the mesh would lose its " +
              std::to_string(mesh.faces.size()) + " faces (write to_cloud(mesh) if that is what you want)");
}

}  // namespace

std::string file_extension(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t name_start = slash == std::string::npos ? 0 : slash + 1;
  const std::size_t dot = path.find_last_of('.');
  // A leading dot names a hidden file (".ply" is a name, not an extension).
  if (dot == std::string::npos || dot <= name_start) return "";
  std::string extension = path.substr(dot);
  for (char& c : extension) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return extension;
}

Mesh read_geometry(const std::string& path, const ReadOptions& options, ReadReport* report) {
  ReadReport local;
  ReadReport& out = report != nullptr ? *report : local;
  Mesh mesh = read_by_format(path, options, out);
  apply_non_finite_policy(path, options.non_finite, mesh, out);
  return mesh;
}

Mesh read_mesh(const std::string& path, const ReadOptions& options, ReadReport* report) {
  Mesh mesh = read_geometry(path, options, report);
  if (!mesh.has_faces()) {
    throw Error(path + ": holds no faces (" + std::to_string(mesh.vertices.size()) +
                " points only), but a mesh is needed here");
  }
  return mesh;
}

Cloud read_cloud(const std::string& path, const ReadOptions& options, ReadReport* report) {
  return to_cloud(read_geometry(path, options, report));
}

void write_mesh(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  const Format format = format_of(path);
  check_consistent(mesh, path.c_str());
  switch (format) {
    case Format::kCad:
      throw Error(path + ": conform reads STEP and IGES but does not write them (write .ply, .stl or .obj)");
    case Format::kPly:
      return detail::write_ply(path, mesh, options);
    case Format::kStl:
      if (!mesh.has_faces()) throw Error(path + ": STL holds only triangles, and the mesh has no faces");
      return detail::write_stl(path, mesh, options);
    case Format::kObj:
      return detail::write_obj(path, mesh, options);
    case Format::kPointList:
      if (mesh.has_faces()) throw_faces_lost(path, mesh);
      return detail::write_point_list(path, mesh, options);
    case Format::kPcd:
      if (mesh.has_faces()) throw_faces_lost(path, mesh);
      return detail::write_pcd(path, to_cloud(mesh), options);
  }
}

void write_cloud(const std::string& path, const Cloud& cloud, const WriteOptions& options) {
  const Format format = format_of(path);
  check_consistent(cloud, path.c_str());
  switch (format) {
    case Format::kCad:
      throw Error(path + ": conform reads STEP and IGES but does not write them (write .ply or .pcd)");
    case Format::kStl:
      throw Error(path + ": STL holds only triangles, not a point cloud (use .ply, .pcd or .xyz)");
    case Format::kPcd:
      return detail::write_pcd(path, cloud, options);
    case Format::kPly:
      return detail::write_ply(path, to_mesh(cloud), options);
    case Format::kObj:
      return detail::write_obj(path, to_mesh(cloud), options);
    case Format::kPointList:
      return detail::write_point_list(path, to_mesh(cloud), options);
  }
}

}  // namespace conform
