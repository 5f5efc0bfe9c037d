// STL writer: binary unless ascii is asked for. STL is single precision by definition, so coordinates are written as
// floats whatever WriteOptions::double_precision says. The facet normals are computed from the corners; the header
// is a fixed text (no date), so that the same mesh always gives the same bytes.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "byte_order.h"
#include "conform/core/error.h"
#include "io_formats.h"
#include "output_file.h"

namespace conform::detail {

namespace {

// Deliberately not starting with "solid": readers that sniff the first bytes would take the file for ascii.
constexpr char kBinaryHeader[] = "binary STL written by conform";

void write_binary(OutputFile& out, const Mesh& mesh) {
  std::string& buffer = out.buffer();
  char header[84] = {};
  std::copy(kBinaryHeader, kBinaryHeader + sizeof(kBinaryHeader) - 1, header);
  store_le(header + 80, static_cast<std::uint32_t>(mesh.faces.size()));
  buffer.append(header, sizeof(header));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    char record[50] = {};  // the trailing uint16 attribute stays 0
    const Eigen::Vector3d n = face_normal(mesh, f);
    for (int k = 0; k < 3; ++k) store_le(record + 4 * k, static_cast<float>(n[k]));
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(c)])];
      for (int k = 0; k < 3; ++k) store_le(record + 12 + 12 * c + 4 * k, static_cast<float>(v[k]));
    }
    buffer.append(record, sizeof(record));
    out.flush_if_full();
  }
}

void append_triple(std::string& out, const Eigen::Vector3d& v) {
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    append_number(out, static_cast<float>(v[k]));
  }
}

void write_ascii(OutputFile& out, const Mesh& mesh) {
  std::string& buffer = out.buffer();
  buffer += "solid conform\n";
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    buffer += "  facet normal";
    append_triple(buffer, face_normal(mesh, f));
    buffer += "\n    outer loop\n";
    for (std::int32_t v : mesh.faces[f]) {
      buffer += "      vertex";
      append_triple(buffer, mesh.vertices[static_cast<std::size_t>(v)]);
      buffer += '\n';
    }
    buffer += "    endloop\n  endfacet\n";
    out.flush_if_full();
  }
  buffer += "endsolid conform\n";
}

}  // namespace

void write_stl(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  if (mesh.faces.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error(path + ": " + std::to_string(mesh.faces.size()) + " triangles are more than binary STL can count");
  }
  OutputFile out(path);
  if (options.encoding == Encoding::kAscii) {
    write_ascii(out, mesh);
  } else {
    write_binary(out, mesh);
  }
  out.commit();
}

}  // namespace conform::detail
