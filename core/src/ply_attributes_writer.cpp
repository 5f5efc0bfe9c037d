// A PLY with per-vertex scalars and colours beside the geometry (conform/core/io.h: write_ply_with_attributes):
// the same header lines and vertex and face records as write_ply (ply_writer.h), with the extra vertex properties
// after x y z (nx ny nz): the scalars as float in the given order, then red green blue as uchar.

#include <algorithm>
#include <cstdint>
#include <string>

#include "byte_order.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "ply_writer.h"

namespace conform {
namespace {

bool is_ply_word(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

void check_attributes(const std::string& path, const Mesh& mesh, const VertexAttributes& attributes) {
  if (file_extension(path) != ".ply") {
    throw Error(path + ": per-vertex attributes are written as .ply only, not '" + file_extension(path) + "'");
  }
  check_consistent(mesh, path.c_str());
  const std::size_t n = mesh.vertices.size();
  for (std::size_t i = 0; i < attributes.scalars.size(); ++i) {
    const auto& [name, values] = attributes.scalars[i];
    if (!is_ply_word(name)) {
      throw Error(path + ": vertex property name '" + name + "' is not a PLY word (letters, digits, '_')");
    }
    for (const char* taken : {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"}) {
      if (name == taken) throw Error(path + ": vertex property name '" + name + "' is taken by the geometry");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (attributes.scalars[j].first == name) throw Error(path + ": vertex property '" + name + "' given twice");
    }
    if (values.size() != n) {
      throw Error(path + ": vertex property '" + name + "' has " + std::to_string(values.size()) + " values for " +
                  std::to_string(n) + " vertices");
    }
  }
  if (!attributes.colors.empty() && attributes.colors.size() != n) {
    throw Error(path + ": " + std::to_string(attributes.colors.size()) + " vertex colours for " + std::to_string(n) +
                " vertices");
  }
}

std::string attribute_properties(const VertexAttributes& attributes) {
  std::string header;
  for (const auto& scalar : attributes.scalars) header += "property float " + scalar.first + "\n";
  if (!attributes.colors.empty()) header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  return header;
}

void append_attributes(std::string& out, const VertexAttributes& attributes, std::size_t i, bool ascii) {
  for (const auto& scalar : attributes.scalars) {
    const float value = scalar.second[i];
    if (ascii) {
      out += ' ';
      detail::append_number(out, value);
    } else {
      char bytes[sizeof(float)];
      detail::store_le(bytes, value);
      out.append(bytes, sizeof(bytes));
    }
  }
  if (attributes.colors.empty()) return;
  for (std::uint8_t channel : attributes.colors[i]) {
    if (ascii) {
      out += ' ';
      detail::append_number(out, std::int64_t{channel});
    } else {
      out += static_cast<char>(channel);
    }
  }
}

}  // namespace

void write_ply_with_attributes(const std::string& path, const Mesh& mesh, const VertexAttributes& attributes,
                               const WriteOptions& options) {
  check_attributes(path, mesh, attributes);
  const bool ascii = options.encoding == Encoding::kAscii;
  detail::OutputFile out(path);
  out.buffer() += detail::ply_header_start(options) + detail::ply_vertex_element(mesh, options) +
                  attribute_properties(attributes) + detail::ply_face_element(mesh) + "end_header\n";
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    detail::append_ply_vertex(out.buffer(), mesh, i, options);
    append_attributes(out.buffer(), attributes, i, ascii);
    if (ascii) out.buffer() += '\n';
    out.flush_if_full();
  }
  detail::write_ply_faces(out, mesh, options);
  out.commit();
}

}  // namespace conform
