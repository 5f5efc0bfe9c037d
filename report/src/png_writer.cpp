#include "conform/report/png_writer.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

#include <zlib.h>

namespace conform {

namespace {

void append_be32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((v >> shift) & 0xffu);
}

// length, type, data, CRC-32 of type and data (PNG specification, section 5.3).
void append_chunk(std::string& out, const char* type, const std::string& data) {
  append_be32(out, static_cast<std::uint32_t>(data.size()));
  const std::string typed = std::string(type, 4) + data;
  out += typed;
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(typed.data()),
                          static_cast<uInt>(typed.size()));
  append_be32(out, static_cast<std::uint32_t>(crc));
}

}  // namespace

std::string encode_png_bgr(const unsigned char* bgr, int width, int height, std::size_t row_bytes) {
  const auto w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  std::vector<unsigned char> raw;
  raw.reserve(h * (3 * w + 1));
  for (std::size_t y = 0; y < h; ++y) {
    raw.push_back(0);  // filter type None
    const unsigned char* row = bgr + y * row_bytes;
    for (std::size_t x = 0; x < w; ++x) raw.insert(raw.end(), {row[3 * x + 2], row[3 * x + 1], row[3 * x]});
  }
  uLongf packed_size = compressBound(static_cast<uLong>(raw.size()));
  std::string packed(packed_size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(packed.data()), &packed_size, raw.data(), static_cast<uLong>(raw.size()),
                9) != Z_OK) {
    throw std::runtime_error("zlib could not compress the PNG image");
  }
  packed.resize(packed_size);

  std::string header;
  append_be32(header, static_cast<std::uint32_t>(width));
  append_be32(header, static_cast<std::uint32_t>(height));
  header += std::string("\x08\x02\x00\x00\x00", 5);  // 8 bits, RGB, deflate, filter method 0, no interlace
  std::string png("\x89PNG\r\n\x1a\n", 8);
  append_chunk(png, "IHDR", header);
  append_chunk(png, "IDAT", packed);
  append_chunk(png, "IEND", "");
  return png;
}

}  // namespace conform
