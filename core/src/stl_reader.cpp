// STL reader, binary and ascii. STL stores each triangle's corners by value; the corners are welded into shared
// vertices where their bits are identical (no tolerance: a tolerance would merge distinct vertices of fine meshes).

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "byte_order.h"
#include "conform/core/error.h"
#include "file_bytes.h"
#include "io_formats.h"
#include "text_scanner.h"
#include "vertex_welder.h"

namespace conform::detail {

namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kPreambleBytes = kHeaderBytes + 4;  // header and the uint32 triangle count
constexpr std::size_t kTriangleBytes = 50;                // normal, 3 corners (12 floats) and a uint16 attribute

// The size a binary STL with this file's triangle count must have; 0 when the file is too short for the count.
std::uint64_t binary_size_claimed(std::string_view bytes, std::uint32_t& count) {
  if (bytes.size() < kPreambleBytes) return 0;
  count = load<std::uint32_t>(bytes.data() + kHeaderBytes, true);
  return kPreambleBytes + std::uint64_t{count} * kTriangleBytes;
}

Mesh read_binary(const std::string& path, std::string_view bytes, std::uint32_t count) {
  // A closed triangle mesh has about half as many vertices as triangles.
  VertexWelder welder(path, count / 2 + 16);
  Mesh mesh;
  mesh.faces.resize(count);
  const char* record = bytes.data() + kPreambleBytes;
  for (std::uint32_t t = 0; t < count; ++t, record += kTriangleBytes) {
    const char* corner = record + 12;  // after the facet normal, which is recomputed from the corners when needed
    Face& face = mesh.faces[t];
    for (int k = 0; k < 3; ++k, corner += 12) {
      face[static_cast<std::size_t>(k)] =
          welder.add(load<float>(corner, true), load<float>(corner + 4, true), load<float>(corner + 8, true));
    }
  }
  mesh.vertices = welder.vertices();
  return mesh;
}

// "solid name / facet normal n n n / outer loop / vertex x y z (3 or more) / endloop / endfacet / endsolid name",
// keywords in any case, several solids in a row allowed.
class AsciiStlParser {
 public:
  AsciiStlParser(const std::string& path, std::string_view text)
      : path_(path), tokens_(text), welder_(path, text.size() / 200) {}

  Mesh parse(ReadReport& report) {
    std::string_view token;
    while (tokens_.next(token)) {
      if (!iequals(token, "solid")) fail("expected 'solid', found " + quoted(token));
      tokens_.skip_line();  // the solid's name
      parse_facets();
    }
    Mesh mesh;
    mesh.vertices = welder_.vertices();
    mesh.faces = std::move(faces_);
    if (short_loops_ > 0) {
      report.warnings.push_back(path_ + ": skipped " + std::to_string(short_loops_) +
                                " facets with fewer than 3 vertices");
    }
    return mesh;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(tokens_.line_number()) + ": " + what);
  }

  static std::string quoted(std::string_view token) { return "'" + std::string(token.substr(0, 40)) + "'"; }

  std::string_view next(const char* expected) {
    std::string_view token;
    if (!tokens_.next(token))
      fail(std::string("unexpected end of file, expected '") + expected + "' (truncated file?)");
    return token;
  }

  void expect(const char* keyword) {
    const std::string_view token = next(keyword);
    if (!iequals(token, keyword)) fail(std::string("expected '") + keyword + "', found " + quoted(token));
  }

  float number() {
    const std::string_view token = next("a number");
    float value = 0.0f;
    if (!parse_number(token, value)) fail(describe_bad_number(token));
    return value;
  }

  void parse_facets() {
    while (true) {
      const std::string_view token = next("endsolid");
      if (iequals(token, "endsolid")) {
        tokens_.skip_line();
        return;
      }
      if (!iequals(token, "facet")) fail("expected 'facet' or 'endsolid', found " + quoted(token));
      expect("normal");
      for (int k = 0; k < 3; ++k) next("a number");  // the facet normal: recomputed from the corners when needed
      expect("outer");
      expect("loop");
      parse_loop();
      expect("endfacet");
    }
  }

  // Loops of more than three corners are fan-triangulated.
  void parse_loop() {
    corners_.clear();
    while (true) {
      const std::string_view token = next("endloop");
      if (iequals(token, "endloop")) break;
      if (!iequals(token, "vertex")) fail("expected 'vertex' or 'endloop', found " + quoted(token));
      const float x = number();
      const float y = number();
      const float z = number();
      corners_.push_back(welder_.add(x, y, z));
    }
    if (corners_.size() < 3) ++short_loops_;
    for (std::size_t k = 1; k + 1 < corners_.size(); ++k) faces_.push_back({corners_[0], corners_[k], corners_[k + 1]});
  }

  const std::string& path_;
  TokenStream tokens_;
  VertexWelder welder_;
  std::vector<Face> faces_;
  std::vector<std::int32_t> corners_;
  std::size_t short_loops_ = 0;
};

bool starts_with_solid(std::string_view bytes) {
  std::string_view first;
  std::string_view probe = bytes.substr(0, 256);
  return next_token(probe, first) && iequals(first, "solid");
}

}  // namespace

// Binary when the size is exactly 84 + 50 * (the header's count): that test is reliable, whereas "starts with
// 'solid'" is not (many binary writers put "solid" in the 80-byte header).
Mesh read_stl(const std::string& path, ReadReport& report) {
  const FileBytes bytes = read_file_bytes(path);
  std::uint32_t count = 0;
  const std::uint64_t claimed = binary_size_claimed(bytes.view(), count);
  if (claimed == bytes.size()) return read_binary(path, bytes.view(), count);

  const std::string as_binary =
      claimed == 0 ? "it is too short for binary STL (" + std::to_string(bytes.size()) + " bytes, less than 84)"
                   : "as binary STL, its header claims " + std::to_string(count) + " triangles (84 + 50 * " +
                         std::to_string(count) + " = " + std::to_string(claimed) + " bytes) but the file has " +
                         std::to_string(bytes.size()) + " bytes";
  if (!starts_with_solid(bytes.view())) {
    throw Error(path + ": not a valid STL file: " + as_binary + ", and it does not start with 'solid' as ascii STL " +
                "does (truncated file?)");
  }
  try {
    return AsciiStlParser(path, bytes.view()).parse(report);
  } catch (const Error& e) {
    if (claimed == 0) throw;
    // A binary file whose header starts with "solid" lands here when its count is wrong: say both readings.
    throw Error(std::string(e.what()) + " (read as ascii STL; " + as_binary + ")");
  }
}

}  // namespace conform::detail
