#pragma once
// The header of a PCD file (PCL's Point Cloud Data format, v0.7), parsed and validated by conform itself: PCL's reader
// is not used. One layout per file: the header's keywords end at the DATA line, and everything after it is the body
// the header describes, whatever it looks like (a binary body may start with text such as "SIZE 8 8 8").

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace conform::detail {

struct PcdField {
  std::string name;
  std::size_t size = 4;  // bytes of one value: 1, 2, 4 or 8 (F: 4 or 8)
  char type = 'F';       // I (signed), U (unsigned) or F (IEEE float)
  std::size_t count = 1;
  std::size_t offset = 0;  // bytes from the start of a point's record (binary) or values before it (ascii: index)
  std::size_t first_value = 0;
};

enum class PcdData { kAscii, kBinary, kBinaryCompressed };

struct PcdHeader {
  std::vector<PcdField> fields;
  std::uint64_t width = 0;
  std::uint64_t height = 0;
  std::uint64_t points = 0;
  PcdData data = PcdData::kBinary;
  std::size_t data_offset = 0;  // the first byte after the DATA line
  std::size_t data_line = 0;    // the DATA line's number

  std::size_t point_bytes() const;
  std::size_t values_per_point() const;
  // The field with that name and COUNT 1, or nullptr.
  const PcdField* find(std::string_view name) const;
};

// The most points a PCD file may hold (PCL's clouds index points with int).
constexpr std::uint64_t kMaxPcdPoints = 2147483647;

// Throws conform::Error "path:line: ..." unless the header is complete and consistent: known keywords, each at most
// once, FIELDS before SIZE, TYPE and COUNT with one entry per field, SIZE/TYPE pairs of I1 I2 I4 I8 U1 U2 U4 U8 F4 F8,
// fields x, y and z with COUNT 1, WIDTH x HEIGHT = POINTS <= kMaxPcdPoints, DATA ascii, binary or binary_compressed.
PcdHeader parse_pcd_header(const std::string& path, std::string_view bytes);

}  // namespace conform::detail
