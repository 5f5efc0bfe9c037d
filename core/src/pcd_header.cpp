#include "pcd_header.h"

#include <algorithm>
#include <limits>
#include <vector>

#include <pcl/io/lzf.h>

#include "byte_order.h"
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

namespace {

class PcdHeaderParser {
 public:
  PcdHeaderParser(const std::string& path, std::string_view bytes) : path_(path), lines_(bytes) {}

  PcdHeader parse() {
    std::string_view line;
    while (lines_.next(line)) {
      std::string_view rest = line;
      std::string_view keyword;
      // PCL splits header lines at spaces, tabs and CRs only: other control characters would make it count
      // differently from us.
      for (char c : line) {
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') fail("control character in the PCD header");
      }
      if (!next_token(rest, keyword) || keyword[0] == '#') continue;
      std::vector<std::string_view> values;
      std::string_view token;
      while (next_token(rest, token)) values.push_back(token);
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

  std::uint64_t count(std::string_view token) const {
    std::int64_t value = 0;
    if (!parse_number(token, value) || value < 0) fail(describe_bad_number(token, true) + " (expected a count)");
    return static_cast<std::uint64_t>(value);
  }

  std::uint64_t single(const std::vector<std::string_view>& values, const char* keyword) const {
    if (values.size() != 1) fail(std::string(keyword) + " must have one value");
    return count(values[0]);
  }

  // PCL's reader fails (printing) unless FIELDS, SIZE, TYPE and COUNT come in this order, and VIEWPOINT has 7 values.
  void keyword_line(std::string_view keyword, const std::vector<std::string_view>& values) {
    if (keyword == "VERSION") return;
    if (keyword == "VIEWPOINT") {
      double ignored = 0.0;
      if (values.size() != 7) fail("VIEWPOINT must have 7 values (tx ty tz qw qx qy qz)");
      for (std::string_view v : values) {
        if (!parse_number(v, ignored)) fail("VIEWPOINT: " + describe_bad_number(v));
      }
    } else if (keyword == "FIELDS") {
      if (!names_.empty()) fail("FIELDS given twice");
      names_.assign(values.begin(), values.end());
      if (names_.empty()) fail("FIELDS names no field");
    } else if (keyword == "SIZE") {
      if (names_.empty() || !sizes_.empty()) fail("SIZE must come once, after FIELDS");
      sizes_ = values;
    } else if (keyword == "TYPE") {
      if (sizes_.empty() || !types_.empty()) fail("TYPE must come once, after SIZE");
      types_ = values;
    } else if (keyword == "COUNT") {
      if (types_.empty() || !counts_.empty()) fail("COUNT must come once, after TYPE");
      counts_ = values;
    } else if (keyword == "WIDTH") {
      header_.width = single(values, "WIDTH");
      have_width_ = true;
    } else if (keyword == "HEIGHT") {
      header_.height = single(values, "HEIGHT");
      have_height_ = true;
    } else if (keyword == "POINTS") {
      header_.points = single(values, "POINTS");
      have_points_ = true;
    } else {
      fail("unexpected '" + std::string(keyword) + "' in the PCD header");
    }
  }

  void data(const std::vector<std::string_view>& values) {
    if (values.size() != 1) fail("DATA must be ascii, binary or binary_compressed");
    if (values[0] == "ascii") {
      header_.data = PcdData::kAscii;
    } else if (values[0] == "binary") {
      header_.data = PcdData::kBinary;
    } else if (values[0] == "binary_compressed") {
      header_.data = PcdData::kBinaryCompressed;
    } else {
      fail("DATA must be ascii, binary or binary_compressed, not '" + std::string(values[0]) + "'");
    }
    header_.data_offset = lines_.offset();
    header_.data_line = lines_.line_number();
  }

  PcdField field(std::size_t i) const {
    PcdField f;
    f.name = std::string(names_[i]);
    f.size = static_cast<std::size_t>(count(sizes_[i]));
    f.type = types_[i].size() == 1 ? types_[i][0] : '?';
    f.count = counts_.empty() ? 1 : static_cast<std::size_t>(count(counts_[i]));
    const bool size_ok = f.size == 1 || f.size == 2 || f.size == 4 || f.size == 8;
    if (!size_ok || (f.type != 'I' && f.type != 'U' && f.type != 'F') || (f.type == 'F' && f.size < 4)) {
      fail("field '" + f.name + "' has an unsupported SIZE/TYPE (" + std::string(sizes_[i]) + " " +
           std::string(types_[i]) + ")");
    }
    if (f.count == 0 || f.count > 1'000'000) fail("field '" + f.name + "' has a COUNT out of range");
    return f;
  }

  PcdHeader finish() {
    if (names_.empty()) fail("the PCD header has no FIELDS");
    if (sizes_.size() != names_.size() || types_.size() != names_.size() ||
        (!counts_.empty() && counts_.size() != names_.size())) {
      fail("FIELDS, SIZE, TYPE and COUNT do not have the same number of entries");
    }
    for (std::size_t i = 0; i < names_.size(); ++i) header_.fields.push_back(field(i));
    for (const char* name : {"x", "y", "z"}) {
      bool found = false;
      for (const PcdField& f : header_.fields) found = found || (f.name == name && f.count == 1);
      if (!found) fail(std::string("the PCD file has no '") + name + "' field");
    }
    if (!have_width_ || !have_height_ || !have_points_) fail("the PCD header lacks WIDTH, HEIGHT or POINTS");
    if (header_.height != 0 && header_.width > std::numeric_limits<std::uint64_t>::max() / header_.height) {
      fail("WIDTH x HEIGHT is out of range");
    }
    // PCL holds the counts and the data's size in 32 bits.
    const std::uint64_t limit = std::numeric_limits<std::uint32_t>::max();
    if (header_.width > limit || header_.height > limit || header_.points > limit / header_.point_bytes()) {
      fail("more than 4 GB of points: PCL's PCD reader cannot hold them");
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
  bool have_width_ = false, have_height_ = false, have_points_ = false;
};

[[noreturn]] void claims_too_much(const std::string& path, const PcdHeader& header, const std::string& needed,
                                  std::size_t follow) {
  throw Error(path + ": header claims " + std::to_string(header.points) + " points (" + needed + ") but only " +
              std::to_string(follow) + " bytes follow (truncated file?)");
}

void check_binary(const std::string& path, const PcdHeader& header, std::string_view body) {
  const std::uint64_t step = header.point_bytes();
  if (header.points > body.size() / step) {
    const bool exact = header.points <= std::numeric_limits<std::uint64_t>::max() / step;
    claims_too_much(path, header, (exact ? std::to_string(header.points * step) : "more than 2^64") + " bytes",
                    body.size());
  }
}

// LZF encodes at most 264 bytes in a 2-byte back-reference's place, so no payload expands more than this.
constexpr std::uint64_t kMaxLzfExpansion = 132;

void check_compressed(const std::string& path, const PcdHeader& header, std::string_view body) {
  if (body.size() < 8) claims_too_much(path, header, "compressed", body.size());
  const auto compressed = load<std::uint32_t>(body.data(), true);
  const auto uncompressed = load<std::uint32_t>(body.data() + 4, true);
  const std::uint64_t step = header.point_bytes();
  if (header.points > std::numeric_limits<std::uint32_t>::max() / step || uncompressed != header.points * step) {
    throw Error(path + ": compressed PCD data holds " + std::to_string(uncompressed) + " bytes, but " +
                std::to_string(header.points) + " points of " + std::to_string(step) + " bytes are claimed");
  }
  if (compressed > body.size() - 8) {
    claims_too_much(path, header, std::to_string(compressed) + " compressed bytes", body.size() - 8);
  }
  if (uncompressed > std::uint64_t{compressed} * kMaxLzfExpansion + 64) {
    throw Error(path + ": " + std::to_string(compressed) + " compressed bytes cannot hold the " +
                std::to_string(uncompressed) + " bytes the header claims");
  }
  // A trial run of the decompression PCL will do: a damaged payload makes PCL's reader print and fail.
  std::vector<char> out(uncompressed);
  if (uncompressed > 0 && pcl::lzfDecompress(body.data() + 8, compressed, out.data(), uncompressed) != uncompressed) {
    throw Error(path + ": the compressed PCD data is damaged (it does not decompress to " +
                std::to_string(uncompressed) + " bytes)");
  }
}

// The number of values on a body line, split the way PCL's ascii reader splits (at runs of space, tab and CR only);
// throws when one is not a number, which PCL would silently read as 0.
std::size_t count_values(const std::string& where, std::string_view line) {
  std::size_t values = 0;
  std::size_t pos = 0;
  while (true) {
    pos = line.find_first_not_of(" \t\r", pos);
    if (pos == std::string_view::npos) return values;
    const std::size_t end = std::min(line.find_first_of(" \t\r", pos), line.size());
    const std::string_view token = line.substr(pos, end - pos);
    double value = 0.0;
    if (!parse_number(token, value)) {
      throw Error(where + "column " + std::to_string(values + 1) + ": " + describe_bad_number(token));
    }
    ++values;
    pos = end;
  }
}

// PCL reads an ascii body without failing on bad or missing values, so every line is checked here. Like PCL, only
// lines with nothing at all (not even a CR or a space) are skipped.
void check_ascii(const std::string& path, const PcdHeader& header, std::string_view body) {
  if (header.points > body.size() / (2 * header.values_per_point()) + 1) {
    claims_too_much(path, header, "at least " + std::to_string(2 * header.values_per_point()) + " bytes each",
                    body.size());
  }
  std::uint64_t points = 0;
  std::size_t line_number = header.data_line;
  for (std::size_t pos = 0; pos < body.size();) {
    const std::size_t end = std::min(body.find('\n', pos), body.size());
    const std::string_view line = body.substr(pos, end - pos);
    pos = end + 1;
    ++line_number;
    if (line.empty()) continue;
    const std::string where = path + ":" + std::to_string(line_number) + ": ";
    const std::size_t values = count_values(where, line);
    if (values != header.values_per_point()) {
      throw Error(where + "expected " + std::to_string(header.values_per_point()) + " values, found " +
                  std::to_string(values));
    }
    if (++points > header.points) throw Error(where + "more points than the header's " + std::to_string(header.points));
  }
  if (points < header.points) {
    throw Error(path + ": header claims " + std::to_string(header.points) + " points but the file holds " +
                std::to_string(points) + " (truncated file?)");
  }
}

}  // namespace

PcdHeader check_pcd(const std::string& path, std::string_view bytes) {
  PcdHeader header = PcdHeaderParser(path, bytes).parse();
  const std::string_view body = bytes.substr(header.data_offset);
  switch (header.data) {
    case PcdData::kBinary:
      check_binary(path, header, body);
      break;
    case PcdData::kBinaryCompressed:
      check_compressed(path, header, body);
      break;
    case PcdData::kAscii:
      check_ascii(path, header, body);
      break;
  }
  return header;
}

}  // namespace conform::detail
