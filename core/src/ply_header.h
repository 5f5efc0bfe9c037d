#pragma once
// The header of a PLY file (Greg Turk's format: "ply", "format ...", "element <name> <count>",
// "property <type> <name>", "property list <count type> <item type> <name>", "end_header").

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace conform::detail {

enum class PlyFormat { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

enum class PlyType : std::uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

std::size_t ply_type_size(PlyType type);
bool ply_type_is_integer(PlyType type);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // of the value, or of the list's items
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;  // lists only
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;

  // The index of the property called `name`, -1 when there is none.
  int find(std::string_view property_name) const;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::kAscii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;      // the first byte after "end_header\n"
  std::size_t end_header_line = 0;  // its line number, for the ascii body's line numbers
};

// Parses the header at the start of `bytes`; throws conform::Error naming `path` and the line when it is malformed.
PlyHeader parse_ply_header(const std::string& path, std::string_view bytes);

// Throws conform::Error when the smallest body the header's counts allow is larger than what follows the header
// ("header claims N vertices (B bytes) but only M bytes follow"), so that no reader allocates for counts that the
// file cannot hold.
void check_ply_body_size(const std::string& path, const PlyHeader& header, std::size_t file_size);

}  // namespace conform::detail
