// Point lists (.xyz .txt .asc .csv): one point per line, values separated by whitespace, commas or semicolons.
// An optional header line (also as a comment, "# x y z nx ny nz") names the columns; without one, the first three
// columns are x y z and any others (intensity, colour) are ignored.

#include <algorithm>
#include <array>
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

// The fields of a data or header line. Semicolons or else commas, when the line has any, separate the fields (which
// may then hold spaces around the value); otherwise whitespace does. Semicolons first: files that use them usually do
// so because the comma is their decimal separator.
void split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  const char separator = line.find(';') != std::string_view::npos   ? ';'
                         : line.find(',') != std::string_view::npos ? ','
                                                                    : '\0';
  if (separator == '\0') {
    std::string_view token;
    while (next_token(line, token)) fields.push_back(token);
    return;
  }
  while (true) {
    const std::size_t end = line.find(separator);
    fields.push_back(trim(line.substr(0, end)));
    if (end == std::string_view::npos) return;
    line.remove_prefix(end + 1);
  }
}

// Column of x y z nx ny nz; -1 for a normal component the file does not have.
using Columns = std::array<int, 6>;

int role_of(std::string_view field) {
  if (field.size() >= 2 && (field.front() == '"' || field.front() == '\'') && field.back() == field.front()) {
    field = field.substr(1, field.size() - 2);
  }
  static const char* const kNames[][3] = {{"x", "x", "x"},
                                          {"y", "y", "y"},
                                          {"z", "z", "z"},
                                          {"nx", "normal_x", "normalx"},
                                          {"ny", "normal_y", "normaly"},
                                          {"nz", "normal_z", "normalz"}};
  for (int role = 0; role < 6; ++role) {
    for (const char* name : kNames[role]) {
      if (iequals(field, name)) return role;
    }
  }
  return -1;
}

// The columns a header line names; false when it does not name all of x, y and z.
bool parse_header(const std::vector<std::string_view>& fields, Columns& columns) {
  Columns found = {-1, -1, -1, -1, -1, -1};
  for (std::size_t c = 0; c < fields.size(); ++c) {
    const int role = role_of(fields[c]);
    if (role >= 0 && found[static_cast<std::size_t>(role)] < 0) {
      found[static_cast<std::size_t>(role)] = static_cast<int>(c);
    }
  }
  if (found[0] < 0 || found[1] < 0 || found[2] < 0) return false;
  if (found[3] < 0 || found[4] < 0 || found[5] < 0) found[3] = found[4] = found[5] = -1;
  columns = found;
  return true;
}

std::string_view comment_body(std::string_view line) {
  if (starts_with(line, "#")) return line.substr(1);
  if (starts_with(line, "//")) return line.substr(2);
  return {};
}

class PointListParser {
 public:
  PointListParser(const std::string& path, std::string_view text) : path_(path), lines_(text) {}

  Mesh parse() {
    std::string_view line;
    while (lines_.next(line)) {
      line = trim(line);
      if (line.empty()) continue;
      const bool comment = starts_with(line, "#") || starts_with(line, "//");
      if (comment) {
        if (!started_) try_header(comment_body(line), true);
        continue;
      }
      split_fields(line, fields_);
      double ignored = 0.0;
      if (!started_ && !parse_number(fields_[0], ignored)) {
        if (!try_header(line, false)) {
          fail(1, describe_bad_number(fields_[0]) + " (nor is the line a header naming x, y, z)");
        }
        continue;
      }
      started_ = true;
      add_point();
    }
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(std::size_t column, const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(lines_.line_number()) + ": column " + std::to_string(column) + ": " +
                what);
  }

  // A header names the columns once, before the first point. A comment is taken for one only when it starts with a
  // column name, so that "# scanned with x y z offsets" does not shift the columns.
  bool try_header(std::string_view line, bool in_comment) {
    if (have_header_) return false;
    std::vector<std::string_view> fields;
    split_fields(line, fields);
    if (fields.empty() || (in_comment && role_of(fields[0]) < 0)) return false;
    have_header_ = parse_header(fields, columns_);
    return have_header_;
  }

  void add_point() {
    const int roles = columns_[3] >= 0 ? 6 : 3;
    double value[6] = {0, 0, 0, 0, 0, 0};
    for (int r = 0; r < roles; ++r) {
      const auto c = static_cast<std::size_t>(columns_[static_cast<std::size_t>(r)]);
      if (c >= fields_.size()) {
        throw Error(path_ + ":" + std::to_string(lines_.line_number()) + ": expected at least " +
                    std::to_string(max_column() + 1) + " columns, found " + std::to_string(fields_.size()));
      }
      if (!parse_number(fields_[c], value[r])) fail(c + 1, describe_bad_number(fields_[c]));
    }
    mesh_.vertices.emplace_back(value[0], value[1], value[2]);
    if (roles == 6) mesh_.normals.emplace_back(value[3], value[4], value[5]);
  }

  int max_column() const {
    int m = 0;
    for (int c : columns_) m = std::max(m, c);
    return m;
  }

  const std::string& path_;
  LineScanner lines_;
  std::vector<std::string_view> fields_;
  Columns columns_ = {0, 1, 2, -1, -1, -1};
  bool have_header_ = false;
  bool started_ = false;
  Mesh mesh_;
};

}  // namespace

Mesh read_point_list(const std::string& path, ReadReport& /*report*/) {
  const FileBytes bytes = read_file_bytes(path);
  return PointListParser(path, bytes.view()).parse();
}

void write_point_list(const std::string& path, const Mesh& mesh, const WriteOptions& options) {
  const bool csv = file_extension(path) == ".csv";
  const char separator = csv ? ',' : ' ';
  OutputFile out(path);
  std::string& buffer = out.buffer();
  if (csv) {
    buffer += mesh.has_normals() ? "x,y,z,nx,ny,nz\n" : "x,y,z\n";
  } else {
    buffer += mesh.has_normals() ? "# x y z nx ny nz\n" : "# x y z\n";
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (k > 0) buffer += separator;
      append_coordinate(buffer, mesh.vertices[i][k], options.double_precision);
    }
    if (mesh.has_normals()) {
      for (int k = 0; k < 3; ++k) {
        buffer += separator;
        append_coordinate(buffer, mesh.normals[i][k], options.double_precision);
      }
    }
    buffer += '\n';
    out.flush_if_full();
  }
  out.commit();
}

}  // namespace conform::detail
