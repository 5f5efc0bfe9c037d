#pragma once
// Reads every scalar vertex property of a PLY file (ascii or binary little-endian) by name, independently of
// conform's reader, which ignores the properties it does not know: tests read back what the writers add
// (e.g. `deviation_mm`, `red`). Header-only; a malformed file fails the calling test through the returned error.

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace conform::test {

struct PlyVertexProperties {
  std::string error;                                  // empty when the file was read
  std::vector<std::string> names;                     // in file order
  std::map<std::string, std::vector<double>> values;  // name -> one value per vertex
};

inline PlyVertexProperties read_ply_vertex_properties(const std::string& bytes) {
  PlyVertexProperties out;
  const std::size_t end = bytes.find("end_header\n");
  if (bytes.compare(0, 4, "ply\n") != 0 || end == std::string::npos) {
    out.error = "not a PLY file";
    return out;
  }
  std::istringstream header(bytes.substr(0, end));
  std::string line, format;
  std::size_t count = 0;
  std::vector<std::string> types;
  bool in_vertex = false, vertex_first = true;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string keyword, a, b;
    words >> keyword >> a >> b;
    if (keyword == "format") format = a;
    if (keyword == "element") {
      in_vertex = a == "vertex";
      if (in_vertex) {
        count = std::stoul(b);
      } else if (out.names.empty()) {
        vertex_first = false;
      }
    }
    if (keyword == "property" && in_vertex) {
      if (a == "list") {
        out.error = "list vertex property";
        return out;
      }
      types.push_back(a);
      out.names.push_back(b);
    }
  }
  if (!vertex_first) {
    out.error = "the vertex element is not the first";
    return out;
  }
  std::size_t at = end + std::strlen("end_header\n");
  std::istringstream text(format == "ascii" ? bytes.substr(at) : std::string());
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t j = 0; j < types.size(); ++j) {
      double v = 0.0;
      if (format == "ascii") {
        std::string token;
        text >> token;
        // A float property's text is the float's shortest form: read it as float to get that float back.
        v = types[j] == "float" ? static_cast<double>(std::strtof(token.c_str(), nullptr))
                                : std::strtod(token.c_str(), nullptr);
      } else if (format == "binary_little_endian") {
        const std::string& t = types[j];
        const std::size_t size = (t == "double") ? 8 : (t == "float" || t == "int" || t == "uint") ? 4 : 1;
        if (at + size > bytes.size()) {
          out.error = "truncated";
          return out;
        }
        if (t == "double") {
          std::memcpy(&v, bytes.data() + at, 8);
        } else if (t == "float") {
          float f;
          std::memcpy(&f, bytes.data() + at, 4);
          v = f;
        } else if (t == "uchar") {
          v = static_cast<unsigned char>(bytes[at]);
        } else {
          out.error = "unsupported property type " + t;
          return out;
        }
        at += size;
      } else {
        out.error = "unsupported format " + format;
        return out;
      }
      out.values[out.names[j]].push_back(v);
    }
  }
  return out;
}

}  // namespace conform::test
