// PLY writer: binary little-endian unless ascii is asked for; float vertices unless double precision is asked for.
// The header carries no date or tool version, so that the same mesh always gives the same bytes.

#include <cstdint>
#include <string>

#include "byte_order.h"
#include "io_formats.h"
#include "output_file.h"

namespace conform::detail {

namespace {

std::string ply_header(const Mesh& mesh, const WriteOptions& options) {
  const char* format = options.encoding == Encoding::kAscii ? "ascii" : "binary_little_endian";
  const char* type = options.double_precision ? "double" : "float";
  std::string header = std::string("ply\nformat ") + format + " 1.0\ncomment written by conform\n";
  header += "element vertex " + std::to_string(mesh.vertices.size()) + "\n";
  for (const char* name : {"x", "y", "z"}) header += std::string("property ") + type + " " + name + "\n";
  if (mesh.has_normals()) {
    for (const char* name : {"nx", "ny", "nz"}) header += std::string("property ") + type + " " + name + "\n";
  }
  if (mesh.has_faces()) {
    header += "element face " + std::to_string(mesh.faces.size()) + "\nproperty list uchar int vertex_indices\n";
  }
  return header + "end_header\n";
}

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

void write_binary_body(OutputFile& out, const Mesh& mesh, bool double_precision) {
  std::string& buffer = out.buffer();
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    append_binary(buffer, mesh.vertices[i], double_precision);
    if (mesh.has_normals()) append_binary(buffer, mesh.normals[i], double_precision);
    out.flush_if_full();
  }
  for (const Face& f : mesh.faces) {
    char bytes[1 + 3 * sizeof(std::int32_t)];
    bytes[0] = 3;
    for (int k = 0; k < 3; ++k) store_le(bytes + 1 + k * sizeof(std::int32_t), f[static_cast<std::size_t>(k)]);
    buffer.append(bytes, sizeof(bytes));
    out.flush_if_full();
  }
}

void append_ascii(std::string& out, const Eigen::Vector3d& v, bool double_precision) {
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out += ' ';
    append_coordinate(out, v[k], double_precision);
  }
}

void write_ascii_body(OutputFile& out, const Mesh& mesh, bool double_precision) {
  std::string& buffer = out.buffer();
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    append_ascii(buffer, mesh.vertices[i], double_precision);
    if (mesh.has_normals()) {
      buffer += ' ';
      append_ascii(buffer, mesh.normals[i], double_precision);
    }
    buffer += '\n';
    out.flush_if_full();
  }
  for (const Face& f : mesh.faces) {
    buffer += '3';
    for (std::int32_t v : f) {
      buffer += ' ';
      append_number(buffer, std::int64_t{v});
    }
    buffer += '\n';
    out.flush_if_full();
  }
}

}  // namespace

void write_ply(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  OutputFile out(path);
  out.buffer() += ply_header(mesh, options);
  if (options.encoding == Encoding::kAscii) {
    write_ascii_body(out, mesh, options.double_precision);
  } else {
    write_binary_body(out, mesh, options.double_precision);
  }
  out.commit();
}

}  // namespace conform::detail
