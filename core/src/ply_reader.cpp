// PLY reader. Our own rather than PCL's: pcl::PLYReader does not check the header's counts against the file's size
// (a forged header makes it allocate what the file cannot hold), reports problems by printing rather than with the
// element that is wrong, and is several times slower than decoding the bytes in memory as done here.

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "byte_order.h"
#include "conform/core/error.h"
#include "file_bytes.h"
#include "io_formats.h"
#include "ply_header.h"
#include "text_scanner.h"

namespace conform::detail {

namespace {

// The body of a binary PLY. Every read is bounds-checked: a truncated file is an error naming the element.
class BinarySource {
 public:
  BinarySource(const std::string& path, std::string_view body, std::size_t body_offset, bool little_endian)
      : path_(path),
        begin_(body.data()),
        p_(body.data()),
        end_(body.data() + body.size()),
        body_offset_(body_offset),
        little_endian_(little_endian) {}

  void begin_item(const std::string& element, std::uint64_t index) {
    element_ = &element;
    index_ = index;
  }

  double scalar(PlyType type) {
    if (type == PlyType::kFloat32) return take<float>();
    if (type == PlyType::kFloat64) return take<double>();
    return static_cast<double>(integer(type));
  }

  std::int64_t integer(PlyType type) {
    switch (type) {
      case PlyType::kInt8:
        return take<std::int8_t>();
      case PlyType::kUint8:
        return take<std::uint8_t>();
      case PlyType::kInt16:
        return take<std::int16_t>();
      case PlyType::kUint16:
        return take<std::uint16_t>();
      case PlyType::kInt32:
        return take<std::int32_t>();
      case PlyType::kUint32:
        return take<std::uint32_t>();
      case PlyType::kFloat32:
      case PlyType::kFloat64:
        break;
    }
    fail("expected an integer type");  // the header parser only lets integer types through here
  }

  void skip(PlyType type) {
    need(ply_type_size(type));
    p_ += ply_type_size(type);
  }

  // Throws unless `count` values of `type` follow: checked before a list is read or its space allocated.
  void expect_list(std::uint64_t count, PlyType type) {
    if (count > static_cast<std::uint64_t>(end_ - p_) / ply_type_size(type)) {
      fail("a list of " + std::to_string(count) + " values runs past the end of the file (truncated file?)");
    }
  }

  void skip_list(const PlyProperty& property) {
    const std::int64_t count = integer(property.count_type);
    if (count < 0) fail("negative list length " + std::to_string(count));
    expect_list(static_cast<std::uint64_t>(count), property.type);
    p_ += static_cast<std::size_t>(count) * ply_type_size(property.type);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ": " + *element_ + " " + std::to_string(index_) + ": " + what);
  }

  void finish() {}

 private:
  void need(std::size_t size) {
    if (static_cast<std::size_t>(end_ - p_) < size) {
      fail("the data ends at byte " + std::to_string(body_offset_ + static_cast<std::size_t>(end_ - begin_)) +
           " (truncated file?)");
    }
  }

  template <typename T>
  T take() {
    need(sizeof(T));
    const T value = load<T>(p_, little_endian_);
    p_ += sizeof(T);
    return value;
  }

  const std::string& path_;
  const char* begin_;
  const char* p_;
  const char* end_;
  std::size_t body_offset_;
  bool little_endian_;
  const std::string* element_ = nullptr;
  std::uint64_t index_ = 0;
};

// The body of an ascii PLY, line-aware: each item (vertex, face, ...) is one line holding exactly its values, so that
// an extra or missing value is an error naming its line rather than a shift of every later value into the next item.
// Blank lines are skipped; anything but blank lines after the last item is an error. Integers are checked against
// their property's type (a uchar of 300 is an error, not 44).
class AsciiSource {
 public:
  AsciiSource(const std::string& path, std::string_view body, std::size_t first_line)
      : path_(path), lines_(body, first_line) {}

  void begin_item(const std::string& element, std::uint64_t index) {
    end_line();
    element_ = &element;
    index_ = index;
    values_ = 0;
    while (lines_.next(rest_)) {
      if (!trim(rest_).empty()) return;
    }
    fail("unexpected end of file (truncated file?)");
  }

  // After the last item: nothing but blank lines may follow.
  void finish() {
    end_line();
    std::string_view line;
    while (lines_.next(line)) {
      if (!trim(line).empty()) {
        throw Error(path_ + ":" + std::to_string(lines_.line_number()) +
                    ": more lines than the header's element counts (the data ends before this line)");
      }
    }
  }

  double scalar(PlyType type) {
    if (ply_type_is_integer(type)) return static_cast<double>(integer(type));
    const std::string_view token = next();
    // A float property is read as a float, so that ascii and binary files of the same data give the same doubles.
    if (type == PlyType::kFloat32) {
      float value = 0.0f;
      if (!parse_number(token, value)) fail(describe_bad_number(token));
      return value;
    }
    double value = 0.0;
    if (!parse_number(token, value)) fail(describe_bad_number(token));
    return value;
  }

  std::int64_t integer(PlyType type) {
    const std::string_view token = next();
    std::int64_t value = 0;
    const auto [lo, hi] = integer_range(type);
    if (!parse_number(token, value) || value < lo || value > hi) {
      fail(describe_bad_number(token, true) + " (" + std::to_string(lo) + " to " + std::to_string(hi) + ")");
    }
    return value;
  }

  void skip(PlyType type) { scalar(type); }

  void expect_list(std::uint64_t count, PlyType /*type*/) {
    if (count > rest_.size() / 2 + 1) {
      fail("a list of " + std::to_string(count) + " values does not fit on its line");
    }
  }

  void skip_list(const PlyProperty& property) {
    const std::int64_t count = integer(property.count_type);
    if (count < 0) fail("negative list length " + std::to_string(count));
    expect_list(static_cast<std::uint64_t>(count), property.type);
    for (std::int64_t i = 0; i < count; ++i) scalar(property.type);
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(lines_.line_number()) + ": " + *element_ + " " + std::to_string(index_) +
                ": " + what);
  }

 private:
  static std::pair<std::int64_t, std::int64_t> integer_range(PlyType type) {
    switch (type) {
      case PlyType::kInt8: return {-128, 127};
      case PlyType::kUint8: return {0, 255};
      case PlyType::kInt16: return {-32768, 32767};
      case PlyType::kUint16: return {0, 65535};
      case PlyType::kInt32: return {std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max()};
      default: return {0, std::numeric_limits<std::uint32_t>::max()};
    }
  }

  void end_line() {
    std::string_view token;
    if (element_ != nullptr && next_token(rest_, token)) {
      fail("more values on the line than the element's " + std::to_string(values_) + " ('" +
           std::string(token.substr(0, 40)) + "' is one too many)");
    }
    rest_ = {};
  }

  std::string_view next() {
    std::string_view token;
    if (!next_token(rest_, token)) {
      fail("the line ends after " + std::to_string(values_) + " values (each item is one line holding all its values)");
    }
    ++values_;
    return token;
  }

  const std::string& path_;
  LineScanner lines_;
  std::string_view rest_;
  const std::string* element_ = nullptr;
  std::uint64_t index_ = 0;
  std::size_t values_ = 0;
};

// Which vertex property goes where: 0-2 x y z, 3-5 the normal, -1 ignored.
struct VertexPlan {
  std::vector<int> role;
  bool has_normals = false;
};

VertexPlan plan_vertices(const std::string& path, const PlyElement& vertex, ReadReport& report) {
  static const char* const kNames[6][2] = {{"x", "x"},         {"y", "y"},         {"z", "z"},
                                           {"nx", "normal_x"}, {"ny", "normal_y"}, {"nz", "normal_z"}};
  VertexPlan plan;
  plan.role.assign(vertex.properties.size(), -1);
  int found[6];
  for (int r = 0; r < 6; ++r) {
    found[r] = vertex.find(kNames[r][0]);
    if (found[r] < 0) found[r] = vertex.find(kNames[r][1]);
    if (found[r] >= 0 && vertex.properties[static_cast<std::size_t>(found[r])].is_list) found[r] = -1;
  }
  if (found[0] < 0 || found[1] < 0 || found[2] < 0) {
    throw Error(path + ": the PLY 'vertex' element has no x, y and z properties");
  }
  plan.has_normals = found[3] >= 0 && found[4] >= 0 && found[5] >= 0;
  const int roles = plan.has_normals ? 6 : 3;
  for (int r = 0; r < roles; ++r) plan.role[static_cast<std::size_t>(found[r])] = r;
  std::string ignored;
  for (std::size_t j = 0; j < plan.role.size(); ++j) {
    if (plan.role[j] < 0) ignored += (ignored.empty() ? "" : ", ") + vertex.properties[j].name;
  }
  if (!ignored.empty()) report.warnings.push_back(path + ": ignored vertex properties: " + ignored);
  return plan;
}

// The face property holding the vertex indices, -1 when the face element has none.
int plan_faces(const std::string& path, const PlyElement& face, std::uint64_t vertex_count, ReadReport& report) {
  int index = face.find("vertex_indices");
  if (index < 0) index = face.find("vertex_index");
  if (index < 0) {
    report.warnings.push_back(path + ": the 'face' element has no vertex_indices list: faces ignored");
    return -1;
  }
  const PlyProperty& property = face.properties[static_cast<std::size_t>(index)];
  if (!property.is_list || !ply_type_is_integer(property.type)) {
    throw Error(path + ": the face property '" + property.name + "' must be a list of integers");
  }
  if (face.count > 0 && vertex_count > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max())) {
    throw Error(path + ": " + std::to_string(vertex_count) + " vertices is more than 32-bit face indices can address");
  }
  if (face.properties.size() > 1)
    report.warnings.push_back(path + ": ignored face properties other than " + property.name);
  return index;
}

template <class Source>
void read_vertices(Source& src, const PlyElement& element, const VertexPlan& plan, Mesh& mesh) {
  mesh.vertices.resize(static_cast<std::size_t>(element.count));
  if (plan.has_normals) mesh.normals.resize(mesh.vertices.size());
  double value[6] = {0, 0, 0, 0, 0, 0};
  for (std::uint64_t i = 0; i < element.count; ++i) {
    src.begin_item(element.name, i);
    for (std::size_t j = 0; j < element.properties.size(); ++j) {
      const PlyProperty& p = element.properties[j];
      if (p.is_list) {
        src.skip_list(p);
      } else if (plan.role[j] >= 0) {
        value[plan.role[j]] = src.scalar(p.type);
      } else {
        src.skip(p.type);
      }
    }
    mesh.vertices[i] = Eigen::Vector3d(value[0], value[1], value[2]);
    if (plan.has_normals) mesh.normals[i] = Eigen::Vector3d(value[3], value[4], value[5]);
  }
}

constexpr std::int64_t kMaxPolygonVertices = 1000;

template <class Source>
void read_polygon(Source& src, const PlyProperty& p, std::uint64_t vertex_count, std::vector<std::int32_t>& polygon) {
  const std::int64_t count = src.integer(p.count_type);
  if (count < 0) src.fail("negative list length " + std::to_string(count));
  // Fan triangulation is for the small convex polygons scanner software writes; the cap also bounds memory, which
  // would otherwise grow 12 bytes a triangle for each byte of a 1-byte index list.
  if (count > kMaxPolygonVertices) {
    src.fail("a polygon of " + std::to_string(count) + " vertices (conform reads polygons of up to " +
             std::to_string(kMaxPolygonVertices) + ")");
  }
  src.expect_list(static_cast<std::uint64_t>(count), p.type);
  polygon.resize(static_cast<std::size_t>(count));
  for (std::int32_t& v : polygon) {
    const std::int64_t index = src.integer(p.type);
    if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count) {
      src.fail("refers to vertex " + std::to_string(index) + " but the file has " + std::to_string(vertex_count) +
               " vertices");
    }
    v = static_cast<std::int32_t>(index);
  }
}

// Polygons are fan-triangulated (0, k, k+1): exact for the convex polygons that scanner software writes.
template <class Source>
std::uint64_t read_faces(Source& src, const PlyElement& element, int index_property, std::uint64_t vertex_count,
                         Mesh& mesh) {
  std::uint64_t short_faces = 0;
  std::vector<std::int32_t> polygon;
  mesh.faces.reserve(static_cast<std::size_t>(element.count));
  for (std::uint64_t i = 0; i < element.count; ++i) {
    src.begin_item(element.name, i);
    for (std::size_t j = 0; j < element.properties.size(); ++j) {
      const PlyProperty& p = element.properties[j];
      if (static_cast<int>(j) == index_property) {
        read_polygon(src, p, vertex_count, polygon);
        if (polygon.size() < 3) ++short_faces;
        for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
          mesh.faces.push_back({polygon[0], polygon[k], polygon[k + 1]});
      } else if (p.is_list) {
        src.skip_list(p);
      } else {
        src.skip(p.type);
      }
    }
  }
  return short_faces;
}

template <class Source>
void skip_element(Source& src, const PlyElement& element) {
  if (element.properties.empty()) return;  // nothing to read, however large the count
  for (std::uint64_t i = 0; i < element.count; ++i) {
    src.begin_item(element.name, i);
    for (const PlyProperty& p : element.properties) {
      if (p.is_list) {
        src.skip_list(p);
      } else {
        src.skip(p.type);
      }
    }
  }
}

const PlyElement* find_element(const PlyHeader& header, const char* name) {
  for (const PlyElement& e : header.elements) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

template <class Source>
Mesh read_body(Source& src, const std::string& path, const PlyHeader& header, ReadReport& report) {
  const PlyElement* vertex = find_element(header, "vertex");
  if (vertex == nullptr) throw Error(path + ": the PLY file has no 'vertex' element");
  const VertexPlan plan = plan_vertices(path, *vertex, report);
  const PlyElement* face = find_element(header, "face");
  const int index_property = face != nullptr ? plan_faces(path, *face, vertex->count, report) : -1;
  Mesh mesh;
  std::uint64_t short_faces = 0;
  std::string ignored;
  for (const PlyElement& element : header.elements) {
    if (&element == vertex) {
      read_vertices(src, element, plan, mesh);
    } else if (&element == face && index_property >= 0) {
      short_faces = read_faces(src, element, index_property, vertex->count, mesh);
    } else {
      skip_element(src, element);
      ignored += (ignored.empty() ? "" : ", ") + element.name;
    }
  }
  if (short_faces > 0) {
    report.warnings.push_back(path + ": skipped " + std::to_string(short_faces) + " faces with fewer than 3 vertices");
  }
  src.finish();
  if (!ignored.empty()) report.warnings.push_back(path + ": ignored PLY elements: " + ignored);
  return mesh;
}

}  // namespace

Mesh read_ply(const std::string& path, ReadReport& report) {
  const FileBytes bytes = read_file_bytes(path);
  const PlyHeader header = parse_ply_header(path, bytes.view());
  check_ply_body_size(path, header, bytes.size());
  const std::string_view body = bytes.view().substr(header.data_offset);
  if (header.format == PlyFormat::kAscii) {
    AsciiSource source(path, body, header.end_header_line + 1);
    return read_body(source, path, header, report);
  }
  BinarySource source(path, body, header.data_offset, header.format == PlyFormat::kBinaryLittleEndian);
  return read_body(source, path, header, report);
}

}  // namespace conform::detail
