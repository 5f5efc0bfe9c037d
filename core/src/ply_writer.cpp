// PLY writer: binary little-endian unless ascii is asked for; float vertices unless double precision is asked for.
// The header carries no date or tool version, so that the same mesh always gives the same bytes.

#include "ply_writer.h"

#include <cstdint>
#include <string>

#include "byte_order.h"
#include "io_formats.h"

namespace conform::detail {

namespace {

void append_binary(std::string& out, const Eigen::Vector3d& v, bool double_precision) {
  char bytes[3 * sizeof(double)];
  for (int k = 0; k < 3; ++k) {
    if (double_precision) {
      store_le(bytes + k * sizeof(double), v[k]);
    } else {
      store_le(bytes + k * sizeof(float), static_cast<float>(v[k]));
    }
  }
  out.append(bytes, 3 * (double_precision ? sizeof(double) : sizeof(float)));
}

void append_ascii(std::string& out, const Eigen::Vector3d& v, bool double_precision) {
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out += ' ';
    append_coordinate(out, v[k], double_precision);
  }
}

}  // namespace

std::string ply_header_start(const WriteOptions& options) {
  const char* format = options.encoding == Encoding::kAscii ? "ascii" : "binary_little_endian";
  return std::string("ply\nformat ") + format + " 1.0\ncomment written by conform\n";
}

std::string ply_vertex_element(const Mesh& mesh, const WriteOptions& options) {
  const char* type = options.double_precision ? "double" : "float";
  std::string header = "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
  for (const char* name : {"x", "y", "z"}) header += std::string("property ") + type + " " + name + "\n";
  if (mesh.has_normals()) {
    for (const char* name : {"nx", "ny", "nz"}) header += std::string("property ") + type + " " + name + "\n";
  }
  return header;
}

std::string ply_face_element(const Mesh& mesh) {
  if (!mesh.has_faces()) return "";
  return "element face " + std::to_string(mesh.faces.size()) + "\nproperty list uchar int vertex_indices\n";
}

void append_ply_vertex(std::string& out, const Mesh& mesh, std::size_t i, const WriteOptions& options) {
  if (options.encoding == Encoding::kAscii) {
    append_ascii(out, mesh.vertices[i], options.double_precision);
    if (mesh.has_normals()) {
      out += ' ';
      append_ascii(out, mesh.normals[i], options.double_precision);
    }
  } else {
    append_binary(out, mesh.vertices[i], options.double_precision);
    if (mesh.has_normals()) append_binary(out, mesh.normals[i], options.double_precision);
  }
}

void write_ply_faces(OutputFile& out, const Mesh& mesh, const WriteOptions& options) {
  std::string& buffer = out.buffer();
  for (const Face& f : mesh.faces) {
    if (options.encoding == Encoding::kAscii) {
      buffer += '3';
      for (std::int32_t v : f) {
        buffer += ' ';
        append_number(buffer, std::int64_t{v});
      }
      buffer += '\n';
    } else {
      char bytes[1 + 3 * sizeof(std::int32_t)];
      bytes[0] = 3;
      for (int k = 0; k < 3; ++k) store_le(bytes + 1 + k * sizeof(std::int32_t), f[static_cast<std::size_t>(k)]);
      buffer.append(bytes, sizeof(bytes));
    }
    out.flush_if_full();
  }
}

void write_ply(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  OutputFile out(path);
  out.buffer() +=
      ply_header_start(options) + ply_vertex_element(mesh, options) + ply_face_element(mesh) + "end_header\n";
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    append_ply_vertex(out.buffer(), mesh, i, options);
    if (options.encoding == Encoding::kAscii) out.buffer() += '\n';
    out.flush_if_full();
  }
  write_ply_faces(out, mesh, options);
  out.commit();
}

}  // namespace conform::detail
