#pragma once
// LZF decompression for PCD's binary_compressed body, written from the format's description (liblzf's lzf_d.c
// documents it; PCL's pcl/io/lzf.h implements the same). The stream is a sequence of chunks, each opened by a control
// byte c:
//   c < 32      a literal run: the next c + 1 input bytes are copied to the output;
//   c >= 32     a back-reference: length L = c >> 5 (when L == 7, the next byte is added to it), then one more byte;
//               L + 2 bytes are copied from ((c & 31) << 8) + that byte + 1 bytes behind the output's end
//               (byte by byte: a reference may overlap what it produces).
// A 3-byte chunk produces at most 264 bytes, so no stream expands by more than kMaxLzfExpansion.

#include <cstddef>
#include <string_view>

namespace conform::detail {

constexpr std::size_t kMaxLzfExpansion = 88;

// Decodes `in` into exactly `out_size` bytes at `out`. Every read and write is checked: returns false (having written
// nothing past out + out_size) when the stream is damaged, would produce more or fewer bytes, or refers before the
// output's start.
bool lzf_decompress(std::string_view in, char* out, std::size_t out_size);

}  // namespace conform::detail
