#include "pcd_body.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "byte_order.h"
#include "conform/core/error.h"
#include "lzf.h"
#include "text_scanner.h"

namespace conform::detail {

namespace {

// PCL writes binary PCD in the host's byte order; every PCD in circulation is little-endian.
template <typename T>
double as_double(const char* p) {
  return static_cast<double>(load<T>(p, true));
}

double binary_value(const char* p, const PcdField& f) {
  if (f.type == 'F') return f.size == 4 ? as_double<float>(p) : as_double<double>(p);
  if (f.type == 'I') {
    switch (f.size) {
      case 1: return as_double<std::int8_t>(p);
      case 2: return as_double<std::int16_t>(p);
      case 4: return as_double<std::int32_t>(p);
      default: return as_double<std::int64_t>(p);
    }
  }
  switch (f.size) {
    case 1: return as_double<std::uint8_t>(p);
    case 2: return as_double<std::uint16_t>(p);
    case 4: return as_double<std::uint32_t>(p);
    default: return as_double<std::uint64_t>(p);
  }
}

// The fields conform keeps: x y z, and normal_x normal_y normal_z when all three are there.
struct Wanted {
  const PcdField* xyz[3];
  const PcdField* normal[3];
  bool normals;
  explicit Wanted(const PcdHeader& h)
      : xyz{h.find("x"), h.find("y"), h.find("z")},
        normal{h.find("normal_x"), h.find("normal_y"), h.find("normal_z")},
        normals(normal[0] != nullptr && normal[1] != nullptr && normal[2] != nullptr) {}
};

std::string type_of(const PcdField& f) { return "TYPE " + std::string(1, f.type) + " SIZE " + std::to_string(f.size); }

[[noreturn]] void size_mismatch(const std::string& path, const PcdHeader& header, const std::string& needed,
                                std::size_t found) {
  throw Error(path + ": the header claims " + std::to_string(header.points) + " points (" + needed + ") but " +
              std::to_string(found) + " bytes follow the DATA line (line " + std::to_string(header.data_line) + ")");
}

// `at(j, f)`: where field f of point j starts.
template <typename At>
Mesh extract(const PcdHeader& header, const At& at) {
  const Wanted w(header);
  Mesh mesh;
  const auto n = static_cast<std::size_t>(header.points);
  mesh.vertices.resize(n);
  if (w.normals) mesh.normals.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    for (int k = 0; k < 3; ++k) mesh.vertices[j][k] = binary_value(at(j, *w.xyz[k]), *w.xyz[k]);
    if (!w.normals) continue;
    for (int k = 0; k < 3; ++k) mesh.normals[j][k] = binary_value(at(j, *w.normal[k]), *w.normal[k]);
  }
  return mesh;
}

Mesh decode_binary(const std::string& path, const PcdHeader& header, std::string_view body) {
  const std::size_t step = header.point_bytes();
  if (header.points > body.size() / step || header.points * step != body.size()) {
    const bool fits = header.points <= std::numeric_limits<std::size_t>::max() / step;
    size_mismatch(path, header, (fits ? std::to_string(header.points * step) : "more than 2^64") + " bytes",
                  body.size());
  }
  return extract(header, [&](std::size_t j, const PcdField& f) { return body.data() + j * step + f.offset; });
}

// binary_compressed: two little-endian uint32 (compressed and uncompressed size), then the LZF stream of the
// points stored field by field (all points' x, then all y, ...), each field's COUNT values of a point together.
Mesh decode_compressed(const std::string& path, const PcdHeader& header, std::string_view body) {
  if (body.size() < 8) size_mismatch(path, header, "8 bytes of sizes and the compressed data", body.size());
  const std::uint64_t compressed = load<std::uint32_t>(body.data(), true);
  const std::uint64_t uncompressed = load<std::uint32_t>(body.data() + 4, true);
  const std::size_t step = header.point_bytes();
  if (header.points > uncompressed / step || header.points * step != uncompressed) {
    throw Error(path + ": compressed PCD data holds " + std::to_string(uncompressed) + " bytes, but " +
                std::to_string(header.points) + " points of " + std::to_string(step) + " bytes are claimed");
  }
  if (compressed != body.size() - 8) {
    size_mismatch(path, header, std::to_string(compressed) + " compressed bytes", body.size() - 8);
  }
  // Checked before allocating: no LZF stream expands more than this, whatever its header says.
  if (uncompressed > compressed * kMaxLzfExpansion) {
    throw Error(path + ": " + std::to_string(compressed) + " compressed bytes cannot hold the " +
                std::to_string(uncompressed) + " bytes the header claims (LZF expands at most " +
                std::to_string(kMaxLzfExpansion) + " times)");
  }
  std::unique_ptr<char[]> data(new char[uncompressed]);
  if (!lzf_decompress(body.substr(8), data.get(), uncompressed)) {
    throw Error(path + ": the compressed PCD data is damaged (it does not decompress to " +
                std::to_string(uncompressed) + " bytes)");
  }
  const std::size_t n = static_cast<std::size_t>(header.points);
  const char* base = data.get();
  return extract(header,
                 [&](std::size_t j, const PcdField& f) { return base + n * f.offset + j * f.size * f.count; });
}

// One ascii value checked against its field: an integer field takes integers within its range, a float field any
// number its SIZE can hold (and nan or inf, which the NonFinitePolicy judges later).
double ascii_value(std::string_view token, const PcdField& f, const std::string& where) {
  const auto bad = [&](const std::string& why) -> Error {
    return Error(where + "field '" + f.name.substr(0, 40) + "' (" + type_of(f) + "): " + why);
  };
  if (f.type == 'F') {
    double v = 0.0;
    if (!parse_number(token, v)) throw bad(describe_bad_number(token));
    if (f.size == 4 && std::isfinite(v) && std::fabs(v) > std::numeric_limits<float>::max()) {
      throw bad(describe_bad_number(token) + " for a 4-byte float");
    }
    return f.size == 4 ? static_cast<double>(static_cast<float>(v)) : v;
  }
  const unsigned bits = static_cast<unsigned>(8 * f.size);
  if (f.type == 'I') {
    std::int64_t v = 0;
    const std::int64_t hi = bits == 64 ? std::numeric_limits<std::int64_t>::max() : (std::int64_t{1} << (bits - 1)) - 1;
    if (!parse_number(token, v) || v > hi || v < -hi - 1) {
      throw bad(describe_bad_number(token, true) + " (" + std::to_string(-hi - 1) + " to " + std::to_string(hi) + ")");
    }
    return static_cast<double>(v);
  }
  std::uint64_t v = 0;
  const std::uint64_t hi = bits == 64 ? std::numeric_limits<std::uint64_t>::max() : (std::uint64_t{1} << bits) - 1;
  if (!parse_number(token, v) || v > hi) {
    throw bad(describe_bad_number(token, true) + " (0 to " + std::to_string(hi) + ")");
  }
  return static_cast<double>(v);
}

class AsciiBody {
 public:
  AsciiBody(const std::string& path, const PcdHeader& header) : path_(path), header_(header), wanted_(header) {}

  Mesh decode(std::string_view body) {
    const std::size_t values = header_.values_per_point();
    if (header_.points > 0 && (values > body.size() / 2 || header_.points > body.size() / (2 * values) + 1)) {
      size_mismatch(path_, header_, "at least " + std::to_string(2 * values) + " bytes each", body.size());
    }
    const auto n = static_cast<std::size_t>(header_.points);
    mesh_.vertices.resize(n);
    if (wanted_.normals) mesh_.normals.resize(n);
    std::size_t line_number = header_.data_line;
    for (std::size_t pos = 0; pos < body.size();) {
      const std::size_t end = std::min(body.find('\n', pos), body.size());
      line(body.substr(pos, end - pos), ++line_number);
      pos = end + 1;
    }
    if (points_ < n) {
      throw Error(path_ + ": the header claims " + std::to_string(n) + " points but the file holds " +
                  std::to_string(points_) + " (truncated file?)");
    }
    return std::move(mesh_);
  }

 private:
  void line(std::string_view text, std::size_t number) {
    std::size_t pos = text.find_first_not_of(" \t\r");
    if (pos == std::string_view::npos) return;  // blank
    const std::string where = path_ + ":" + std::to_string(number) + ": ";
    if (points_ == header_.points) {
      throw Error(where + "more points than the header's " + std::to_string(header_.points));
    }
    std::size_t found = 0, field = 0, within = 0;
    for (; pos != std::string_view::npos; pos = text.find_first_not_of(" \t\r", pos)) {
      const std::size_t end = std::min(text.find_first_of(" \t\r", pos), text.size());
      const std::string_view token = text.substr(pos, end - pos);
      pos = end;
      if (field == header_.fields.size()) {
        ++found;
        continue;
      }
      const PcdField& f = header_.fields[field];
      const double v = ascii_value(token, f, where);
      keep(f, v);
      ++found;
      if (++within == f.count) ++field, within = 0;
    }
    if (found != header_.values_per_point()) {
      throw Error(where + "expected " + std::to_string(header_.values_per_point()) + " values, found " +
                  std::to_string(found));
    }
    ++points_;
  }

  void keep(const PcdField& f, double v) {
    for (int k = 0; k < 3; ++k) {
      if (&f == wanted_.xyz[k]) mesh_.vertices[points_][k] = v;
      if (wanted_.normals && &f == wanted_.normal[k]) mesh_.normals[points_][k] = v;
    }
  }

  const std::string& path_;
  const PcdHeader& header_;
  Wanted wanted_;
  Mesh mesh_;
  std::size_t points_ = 0;
};

}  // namespace

Mesh decode_pcd_body(const std::string& path, const PcdHeader& header, std::string_view body) {
  switch (header.data) {
    case PcdData::kBinary:
      return decode_binary(path, header, body);
    case PcdData::kBinaryCompressed:
      return decode_compressed(path, header, body);
    case PcdData::kAscii:
      break;
  }
  return AsciiBody(path, header).decode(body);
}

}  // namespace conform::detail
