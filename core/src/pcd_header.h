#pragma once
// Our own check of a PCD file before PCL's reader sees it. pcl::PCDReader (PCL 1.13) allocates whatever the header
// claims before looking at the file's size (1.2 GB for a 200-byte file claiming 10^8 points; std::bad_alloc for
// 4e9), crashes on a header without FIELDS, turns non-numeric ascii values into 0 and short ascii lines into zeros
// without failing, and prints its complaints to the console. So the header is validated against the file here, and
// an ascii body token by token, and PCL is called only on files it reads correctly.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace conform::detail {

struct PcdField {
  std::string name;
  std::size_t size = 4;  // bytes of one value: 1, 2, 4 or 8
  char type = 'F';       // I, U or F
  std::size_t count = 1;
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
};

// Throws conform::Error naming `path` (and the line) unless the header is complete and consistent, has x, y and z,
// and the body holds exactly the points it claims (for ascii: that many lines of that many numbers; for
// binary_compressed: a payload that decompresses to them).
PcdHeader check_pcd(const std::string& path, std::string_view bytes);

}  // namespace conform::detail
