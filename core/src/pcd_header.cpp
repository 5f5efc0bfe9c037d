#include "pcd_header.h"

#include <limits>
#include <utility>
#include <vector>

#include "conform/core/error.h"
#include "text_scanner.h"

namespace conform::detail {

std::size_t PcdHeader::point_bytes() const {
  std::size_t bytes = 0;
  for (const PcdField& f : fields) bytes += f.size * f.count;
  return bytes;
}

std::size_t PcdHeader::values_per_point() const {
  std::size_t values = 0;
  for (const PcdField& f : fields) values += f.count;
  return values;
}

const PcdField* PcdHeader::find(std::string_view name) const {
  for (const PcdField& f : fields) {
    if (f.name == name && f.count == 1) return &f;
  }
  return nullptr;
}

namespace {

constexpr std::size_t kMaxFields = 1000;
constexpr std::uint64_t kMaxCount = 1'000'000;

class PcdHeaderParser {
 public:
  PcdHeaderParser(const std::string& path, std::string_view bytes) : path_(path), lines_(bytes) {}

  PcdHeader parse() {
    std::string_view line;
    while (lines_.next(line)) {
      for (char c : line) {
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') fail("control character in the PCD header");
      }
      std::string_view rest = line;
      std::string_view keyword;
      if (!next_token(rest, keyword) || keyword[0] == '#') continue;  // blank (or only spaces) or a comment
      std::vector<std::string_view> values;
      std::string_view token;
      while (next_token(rest, token)) {
        if (values.size() == kMaxFields) fail(std::string(keyword) + " has more than " + std::to_string(kMaxFields) + " values");
        values.push_back(token);
      }
      if (keyword == "DATA") {
        data(values);
        return finish();
      }
      keyword_line(keyword, values);
    }
    throw Error(path_ + ": PCD header has no DATA line (not a PCD file, or truncated)");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(lines_.line_number()) + ": " + what);
  }

  std::uint64_t count(std::string_view token, const std::string& what) const {
    std::uint64_t value = 0;
    if (!parse_number(token, value)) fail(what + ": " + describe_bad_number(token, true) + " (expected a count)");
    return value;
  }

  std::uint64_t single(const std::vector<std::string_view>& values, const char* keyword, bool& seen) const {
    if (seen) fail(std::string(keyword) + " given twice");
    seen = true;
    if (values.size() != 1) fail(std::string(keyword) + " must have one value");
    return count(values[0], keyword);
  }

  void list(std::vector<std::string_view>& to, const std::vector<std::string_view>& values, const char* keyword) {
    if (names_.empty() || !to.empty()) fail(std::string(keyword) + " must come once, after FIELDS");
    if (values.size() != names_.size()) {
      fail(std::string(keyword) + " has " + std::to_string(values.size()) + " entries for " +
           std::to_string(names_.size()) + " FIELDS");
    }
    to = values;
  }

  void keyword_line(std::string_view keyword, const std::vector<std::string_view>& values) {
    if (keyword == "VERSION") {
      if (seen_version_) fail("VERSION given twice");
      seen_version_ = true;
    } else if (keyword == "VIEWPOINT") {
      if (seen_viewpoint_) fail("VIEWPOINT given twice");
      seen_viewpoint_ = true;
      double ignored = 0.0;
      if (values.size() != 7) fail("VIEWPOINT must have 7 values (tx ty tz qw qx qy qz)");
      for (std::string_view v : values) {
        if (!parse_number(v, ignored)) fail("VIEWPOINT: " + describe_bad_number(v));
      }
    } else if (keyword == "FIELDS") {
      if (!names_.empty()) fail("FIELDS given twice");
      names_ = values;
      if (names_.empty()) fail("FIELDS names no field");
    } else if (keyword == "SIZE") {
      list(sizes_, values, "SIZE");
    } else if (keyword == "TYPE") {
      list(types_, values, "TYPE");
    } else if (keyword == "COUNT") {
      list(counts_, values, "COUNT");
    } else if (keyword == "WIDTH") {
      header_.width = single(values, "WIDTH", seen_width_);
    } else if (keyword == "HEIGHT") {
      header_.height = single(values, "HEIGHT", seen_height_);
    } else if (keyword == "POINTS") {
      header_.points = single(values, "POINTS", seen_points_);
    } else {
      fail("unexpected '" + std::string(keyword.substr(0, 40)) + "' in the PCD header");
    }
  }

  void data(const std::vector<std::string_view>& values) {
    if (values.size() == 1 && values[0] == "ascii") {
      header_.data = PcdData::kAscii;
    } else if (values.size() == 1 && values[0] == "binary") {
      header_.data = PcdData::kBinary;
    } else if (values.size() == 1 && values[0] == "binary_compressed") {
      header_.data = PcdData::kBinaryCompressed;
    } else {
      fail("DATA must be ascii, binary or binary_compressed");
    }
    header_.data_offset = lines_.offset();
    header_.data_line = lines_.line_number();
  }

  PcdField field(std::size_t i) const {
    PcdField f;
    f.name = std::string(names_[i]);
    const std::string what = "field '" + f.name.substr(0, 40) + "'";
    const std::uint64_t size = count(sizes_[i], what + " SIZE");
    f.size = static_cast<std::size_t>(size);
    f.type = types_[i].size() == 1 ? types_[i][0] : '?';
    const std::uint64_t n = counts_.empty() ? 1 : count(counts_[i], what + " COUNT");
    const bool size_ok = size == 1 || size == 2 || size == 4 || size == 8;
    if (!size_ok || (f.type != 'I' && f.type != 'U' && f.type != 'F') || (f.type == 'F' && size < 4)) {
      fail(what + " has an unsupported SIZE/TYPE (" + std::string(sizes_[i].substr(0, 20)) + " " +
           std::string(types_[i].substr(0, 20)) + "; supported: I or U of 1, 2, 4 or 8 bytes, F of 4 or 8)");
    }
    if (n == 0 || n > kMaxCount) fail(what + " has a COUNT out of range (1 to " + std::to_string(kMaxCount) + ")");
    f.count = static_cast<std::size_t>(n);
    return f;
  }

  void add_fields() {
    if (names_.empty()) fail("the PCD header has no FIELDS");
    if (sizes_.empty() || types_.empty()) fail("the PCD header lacks SIZE or TYPE");
    std::size_t offset = 0, value = 0;
    for (std::size_t i = 0; i < names_.size(); ++i) {
      PcdField f = field(i);
      for (const PcdField& g : header_.fields) {
        if (g.name == f.name && f.name != "_") fail("field '" + f.name.substr(0, 40) + "' named twice in FIELDS");
      }
      f.offset = offset;
      f.first_value = value;
      offset += f.size * f.count;
      value += f.count;
      header_.fields.push_back(std::move(f));
    }
    for (const char* name : {"x", "y", "z"}) {
      if (header_.find(name) == nullptr) fail(std::string("the PCD file has no '") + name + "' field");
    }
  }

  PcdHeader finish() {
    add_fields();
    if (!seen_width_ || !seen_height_ || !seen_points_) fail("the PCD header lacks WIDTH, HEIGHT or POINTS");
    if (header_.points > kMaxPcdPoints || header_.width > kMaxPcdPoints || header_.height > kMaxPcdPoints) {
      fail("more than " + std::to_string(kMaxPcdPoints) + " points: more than conform reads from one PCD file");
    }
    if (header_.width * header_.height != header_.points) {
      fail("WIDTH x HEIGHT (" + std::to_string(header_.width) + " x " + std::to_string(header_.height) +
           ") is not POINTS (" + std::to_string(header_.points) + ")");
    }
    return std::move(header_);
  }

  const std::string& path_;
  LineScanner lines_;
  PcdHeader header_;
  std::vector<std::string_view> names_, sizes_, types_, counts_;
  bool seen_version_ = false, seen_viewpoint_ = false;
  bool seen_width_ = false, seen_height_ = false, seen_points_ = false;
};

}  // namespace

PcdHeader parse_pcd_header(const std::string& path, std::string_view bytes) {
  return PcdHeaderParser(path, bytes).parse();
}

}  // namespace conform::detail
