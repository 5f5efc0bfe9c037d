#include "ply_header.h"

#include <limits>

#include "conform/core/error.h"
#include "text_scanner.h"

namespace conform::detail {

std::size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

bool ply_type_is_integer(PlyType type) { return type != PlyType::kFloat32 && type != PlyType::kFloat64; }

int PlyElement::find(std::string_view property_name) const {
  for (std::size_t i = 0; i < properties.size(); ++i) {
    if (properties[i].name == property_name) return static_cast<int>(i);
  }
  return -1;
}

namespace {

bool parse_type(std::string_view name, PlyType& type) {
  struct Named {
    const char* name;
    PlyType type;
  };
  // Both the original names and the sized ones that later writers (VTK, Open3D) use.
  static const Named kTypes[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
      {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const Named& t : kTypes) {
    if (name == t.name) {
      type = t.type;
      return true;
    }
  }
  return false;
}

class HeaderParser {
 public:
  HeaderParser(const std::string& path, std::string_view bytes) : path_(path), lines_(bytes) {}

  PlyHeader parse() {
    std::string_view line;
    if (!lines_.next(line) || trim(line) != "ply") throw Error(path_ + ": not a PLY file (does not start with 'ply')");
    bool have_format = false;
    while (lines_.next(line)) {
      std::string_view rest = line;
      std::string_view keyword;
      if (!next_token(rest, keyword)) continue;
      if (keyword == "end_header") {
        if (!have_format) fail("the header has no 'format' line");
        header_.data_offset = lines_.offset();
        header_.end_header_line = lines_.line_number();
        return std::move(header_);
      }
      if (keyword == "comment" || keyword == "obj_info") continue;
      if (keyword == "format") {
        parse_format(rest);
        have_format = true;
      } else if (keyword == "element") {
        parse_element(rest);
      } else if (keyword == "property") {
        parse_property(rest);
      } else {
        fail("unexpected '" + std::string(keyword) + "' in the PLY header");
      }
    }
    throw Error(path_ + ": PLY header has no 'end_header' line (truncated file?)");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(lines_.line_number()) + ": " + what);
  }

  std::string_view expect_token(std::string_view& rest, const char* what) const {
    std::string_view token;
    if (!next_token(rest, token)) fail(std::string("missing ") + what);
    return token;
  }

  void expect_end(std::string_view rest) const {
    std::string_view token;
    if (next_token(rest, token)) fail("unexpected '" + std::string(token) + "' at the end of the line");
  }

  void parse_format(std::string_view rest) {
    const std::string_view name = expect_token(rest, "format name");
    if (name == "ascii") {
      header_.format = PlyFormat::kAscii;
    } else if (name == "binary_little_endian") {
      header_.format = PlyFormat::kBinaryLittleEndian;
    } else if (name == "binary_big_endian") {
      header_.format = PlyFormat::kBinaryBigEndian;
    } else {
      fail("unknown PLY format '" + std::string(name) + "'");
    }
    expect_token(rest, "format version");
  }

  void parse_element(std::string_view rest) {
    PlyElement element;
    element.name = std::string(expect_token(rest, "element name"));
    const std::string_view count = expect_token(rest, "element count");
    if (!parse_number(count, element.count)) {
      fail("element '" + element.name + "': count " + describe_bad_number(count, true));
    }
    expect_end(rest);
    header_.elements.push_back(std::move(element));
  }

  PlyType expect_type(std::string_view& rest) const {
    const std::string_view name = expect_token(rest, "property type");
    PlyType type{};
    if (!parse_type(name, type)) fail("unknown PLY property type '" + std::string(name) + "'");
    return type;
  }

  void parse_property(std::string_view rest) {
    if (header_.elements.empty()) fail("'property' before any 'element'");
    PlyProperty property;
    std::string_view probe = rest;
    std::string_view first;
    if (next_token(probe, first) && first == "list") {
      rest = probe;
      property.is_list = true;
      property.count_type = expect_type(rest);
      if (!ply_type_is_integer(property.count_type)) fail("a list's count type must be an integer type");
    }
    property.type = expect_type(rest);
    property.name = std::string(expect_token(rest, "property name"));
    expect_end(rest);
    header_.elements.back().properties.push_back(std::move(property));
  }

  const std::string& path_;
  LineScanner lines_;
  PlyHeader header_;
};

std::string describe_count(const PlyElement& element) {
  const std::string n = std::to_string(element.count);
  if (element.name == "vertex") return n + (element.count == 1 ? " vertex" : " vertices");
  if (element.name == "face") return n + (element.count == 1 ? " face" : " faces");
  return n + " '" + element.name + "' elements";
}

}  // namespace

PlyHeader parse_ply_header(const std::string& path, std::string_view bytes) {
  return HeaderParser(path, bytes).parse();
}

void check_ply_body_size(const std::string& path, const PlyHeader& header, std::size_t file_size) {
  const bool ascii = header.format == PlyFormat::kAscii;
  // An ascii value takes at least one character and a separator; the file's last value may lack the separator.
  std::uint64_t left = file_size - header.data_offset + (ascii ? 1 : 0);
  for (const PlyElement& element : header.elements) {
    std::uint64_t item_bytes = 0;
    for (const PlyProperty& p : element.properties) {
      item_bytes += ascii ? 2 : ply_type_size(p.is_list ? p.count_type : p.type);
    }
    if (item_bytes == 0 || element.count <= left / item_bytes) {
      left -= element.count * item_bytes;
      continue;
    }
    const bool exact = element.count <= std::numeric_limits<std::uint64_t>::max() / item_bytes;
    const std::string needed = exact ? std::to_string(element.count * item_bytes) : "more than 2^64";
    const std::uint64_t follow = ascii && left > 0 ? left - 1 : left;
    throw Error(path + ": header claims " + describe_count(element) + " (at least " + needed + " bytes) but only " +
                std::to_string(follow) + " bytes follow (truncated file?)");
  }
}

}  // namespace conform::detail
