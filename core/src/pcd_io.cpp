// PCD reading and writing by conform itself (PCL's reader and writer are not used, and conform does not link PCL's io
// library): parse_pcd_header() validates the header, decode_pcd_body() the body. Writing gives the same bytes PCL's
// writer gives for a packed x y z [normal_x normal_y normal_z] float cloud: the header PCL writes, then the floats
// (binary, little-endian) or one line per point with 9 significant digits (ascii, enough for any float).

#include <charconv>
#include <cstdint>
#include <string>

#include "byte_order.h"
#include "conform/core/atomic_file.h"
#include "conform/core/error.h"
#include "file_bytes.h"
#include "io_formats.h"
#include "pcd_body.h"
#include "pcd_header.h"

namespace conform::detail {

namespace {

std::string pcd_header_text(std::size_t points, bool normals, bool ascii) {
  const std::string n = std::to_string(points);
  return std::string("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n") +
         (normals ? "FIELDS x y z normal_x normal_y normal_z\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\nCOUNT 1 1 1 1 1 1\n"
                  : "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n") +
         "WIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA " + (ascii ? "ascii\n" : "binary\n");
}

void append_float(std::string& out, float value) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), value, std::chars_format::general, 9);
  out.append(buffer, r.ptr);
}

}  // namespace

Mesh read_pcd(const std::string& path, ReadReport& /*report*/) {
  const FileBytes bytes = read_file_bytes(path);
  const PcdHeader header = parse_pcd_header(path, bytes.view());
  return decode_pcd_body(path, header, bytes.view().substr(header.data_offset));
}

void write_pcd(const std::string& path, const Cloud& cloud, const WriteOptions& options) {
  const bool ascii = options.encoding == Encoding::kAscii;
  const bool normals = cloud.has_normals();
  std::string text = pcd_header_text(cloud.size(), normals, ascii);
  const std::size_t fields = normals ? 6 : 3;
  text.reserve(text.size() + cloud.size() * fields * (ascii ? 16 : 4));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const float values[6] = {cloud.points[i].x,
                             cloud.points[i].y,
                             cloud.points[i].z,
                             normals ? cloud.normals[i].normal_x : 0.0f,
                             normals ? cloud.normals[i].normal_y : 0.0f,
                             normals ? cloud.normals[i].normal_z : 0.0f};
    for (std::size_t k = 0; k < fields; ++k) {
      if (ascii) {
        if (k > 0) text += ' ';
        append_float(text, values[k]);
      } else {
        char le[4];
        store_le(le, values[k]);
        text.append(le, 4);
      }
    }
    if (ascii) text += '\n';
  }
  write_file_atomically(path, text);
}

}  // namespace conform::detail
