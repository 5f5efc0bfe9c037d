// Wavefront OBJ: "v x y z", "vn x y z" and "f" with v, v/vt, v//vn or v/vt/vn corners (negative indices count back
// from the latest element); polygons are fan-triangulated. Everything else (vt, groups, materials, lines) is ignored:
// conform's meshes have no texture coordinates.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "conform/core/error.h"
#include "file_bytes.h"
#include "io_formats.h"
#include "output_file.h"
#include "text_scanner.h"

namespace conform::detail {

namespace {

class ObjParser {
 public:
  ObjParser(const std::string& path, std::string_view text) : path_(path), lines_(text) {}

  Mesh parse(ReadReport& report) {
    std::string_view line;
    while (lines_.next(line)) {
      std::string_view rest = line;
      std::string_view keyword;
      if (!next_token(rest, keyword) || keyword[0] == '#') continue;
      if (keyword == "v") {
        vertices_.push_back(triple(rest));
      } else if (keyword == "vn") {
        normals_.push_back(triple(rest));
      } else if (keyword == "f") {
        face(rest);
      }
    }
    if (short_faces_ > 0) {
      report.warnings.push_back(path_ + ": skipped " + std::to_string(short_faces_) +
                                " faces with fewer than 3 vertices");
    }
    Mesh mesh;
    mesh.normals = vertex_normals(report);
    mesh.faces = std::move(faces_);
    mesh.vertices = std::move(vertices_);
    return mesh;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(lines_.line_number()) + ": " + what);
  }

  // Three coordinates; more values (the optional w, or vertex colours) are ignored.
  Eigen::Vector3d triple(std::string_view rest) const {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) {
      std::string_view token;
      if (!next_token(rest, token)) fail("expected 3 coordinates, found " + std::to_string(k));
      if (!parse_number(token, v[k])) fail("column " + std::to_string(k + 2) + ": " + describe_bad_number(token));
    }
    return v;
  }

  // A 1-based index, or a negative one counting back from the last of `count` elements; 0-based on return.
  std::int32_t resolve(std::string_view token, std::size_t count, const char* what, const char* plural) const {
    std::int64_t index = 0;
    if (!parse_number(token, index)) fail(std::string(what) + " index " + describe_bad_number(token, true));
    const std::int64_t n = static_cast<std::int64_t>(count);
    const std::int64_t resolved = index < 0 ? n + index : index - 1;
    if (index == 0 || resolved < 0 || resolved >= n) {
      fail("face refers to " + std::string(what) + " " + std::string(token) + " but " + std::to_string(count) + " " +
           (count == 1 ? std::string(what) + " is" : std::string(plural) + " are") + " defined so far");
    }
    return static_cast<std::int32_t>(resolved);
  }

  void face(std::string_view rest) {
    corners_.clear();
    corner_normals_.clear();
    std::string_view token;
    while (next_token(rest, token)) {
      const std::size_t slash = token.find('/');
      corners_.push_back(resolve(token.substr(0, slash), vertices_.size(), "vertex", "vertices"));
      const std::size_t second = slash == std::string_view::npos ? slash : token.find('/', slash + 1);
      const std::string_view normal = second == std::string_view::npos ? std::string_view() : token.substr(second + 1);
      corner_normals_.push_back(normal.empty() ? -1 : resolve(normal, normals_.size(), "normal", "normals"));
    }
    if (corners_.size() < 3) ++short_faces_;
    for (std::size_t k = 1; k + 1 < corners_.size(); ++k) {
      faces_.push_back({corners_[0], corners_[k], corners_[k + 1]});
      for (std::size_t c : {std::size_t{0}, k, k + 1}) {
        face_normals_.push_back(corner_normals_[c]);
      }
    }
  }

  // OBJ gives normals per face corner, conform per vertex: they map when each vertex always gets the same normal.
  // Without face references, "vn" lines one per "v" line (a cloud) map in order.
  std::vector<Eigen::Vector3d> vertex_normals(ReadReport& report) const {
    std::vector<Eigen::Vector3d> out;
    if (normals_.empty()) return out;
    std::size_t referenced = 0;
    for (std::int32_t n : face_normals_) referenced += n >= 0 ? 1 : 0;
    if (referenced == 0) {
      if (normals_.size() == vertices_.size()) return normals_;
      report.warnings.push_back(path_ + ": ignored " + std::to_string(normals_.size()) +
                                " normals that no face uses and that are not one per vertex");
      return out;
    }
    out.assign(vertices_.size(), Eigen::Vector3d::Zero());
    std::vector<bool> assigned(vertices_.size(), false);
    for (std::size_t i = 0; i < face_normals_.size(); ++i) {
      const auto v = static_cast<std::size_t>(faces_[i / 3][i % 3]);
      const std::int32_t n = face_normals_[i];
      if (n < 0) return drop_normals("some face corners have no normal", report);
      const Eigen::Vector3d& normal = normals_[static_cast<std::size_t>(n)];
      if (assigned[v] && out[v] != normal) {
        return drop_normals("vertex " + std::to_string(v + 1) + " has different normals in different faces", report);
      }
      out[v] = normal;
      assigned[v] = true;
    }
    for (std::size_t v = 0; v < assigned.size(); ++v) {
      if (!assigned[v]) return drop_normals("vertex " + std::to_string(v + 1) + " is in no face", report);
    }
    return out;
  }

  std::vector<Eigen::Vector3d> drop_normals(const std::string& why, ReadReport& report) const {
    report.warnings.push_back(path_ + ": vertex normals dropped: " + why);
    return {};
  }

  const std::string& path_;
  LineScanner lines_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Eigen::Vector3d> normals_;
  std::vector<Face> faces_;
  std::vector<std::int32_t> face_normals_;  // per triangle corner: the index into normals_, -1 for none
  std::vector<std::int32_t> corners_;
  std::vector<std::int32_t> corner_normals_;
  std::size_t short_faces_ = 0;
};

void append_line(std::string& out, const char* keyword, const Eigen::Vector3d& v, bool double_precision) {
  out += keyword;
  for (int k = 0; k < 3; ++k) {
    out += ' ';
    append_coordinate(out, v[k], double_precision);
  }
  out += '\n';
}

}  // namespace

Mesh read_obj(const std::string& path, ReadReport& report) {
  const FileBytes bytes = read_file_bytes(path);
  return ObjParser(path, bytes.view()).parse(report);
}

void write_obj(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  OutputFile out(path);
  std::string& buffer = out.buffer();
  buffer += "# written by conform\n";
  for (const Eigen::Vector3d& v : mesh.vertices) {
    append_line(buffer, "v", v, options.double_precision);
    out.flush_if_full();
  }
  for (const Eigen::Vector3d& n : mesh.normals) {
    append_line(buffer, "vn", n, options.double_precision);
    out.flush_if_full();
  }
  // Vertex and normal k share index k, so each corner is "k//k".
  for (const Face& f : mesh.faces) {
    buffer += 'f';
    for (std::int32_t v : f) {
      buffer += ' ';
      append_number(buffer, std::int64_t{v} + 1);
      if (mesh.has_normals()) {
        buffer += "//";
        append_number(buffer, std::int64_t{v} + 1);
      }
    }
    buffer += '\n';
    out.flush_if_full();
  }
  out.commit();
}

}  // namespace conform::detail
