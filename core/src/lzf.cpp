#include "lzf.h"

namespace conform::detail {

bool lzf_decompress(std::string_view in, char* out, std::size_t out_size) {
  std::size_t i = 0;  // next input byte
  std::size_t o = 0;  // next output byte
  while (i < in.size()) {
    const auto control = static_cast<unsigned char>(in[i++]);
    if (control < 32) {
      const std::size_t run = std::size_t{control} + 1;
      if (run > in.size() - i || run > out_size - o) return false;
      for (std::size_t k = 0; k < run; ++k) out[o++] = in[i++];
      continue;
    }
    std::size_t length = control >> 5;
    if (length == 7) {
      if (i >= in.size()) return false;
      length += static_cast<unsigned char>(in[i++]);
    }
    if (i >= in.size()) return false;
    const std::size_t back = (std::size_t{control & 31u} << 8) + static_cast<unsigned char>(in[i++]) + 1;
    length += 2;
    if (back > o || length > out_size - o) return false;
    for (std::size_t k = 0; k < length; ++k, ++o) out[o] = out[o - back];
  }
  return o == out_size;
}

}  // namespace conform::detail
