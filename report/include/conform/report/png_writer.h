#pragma once
// PNG encoding of an 8-bit BGR image with zlib, so that `conform` does not link OpenCV's imgcodecs (which pulls GDAL,
// and with it some 60 shared libraries, into every start).

#include <cstddef>
#include <string>

namespace conform {

// The PNG file (colour type 2, RGB, 8 bits, no interlace, filter 0 on every row, zlib level 9) of a `width` x `height`
// image whose rows start `row_bytes` apart at `bgr`, 3 bytes per pixel in B, G, R order. Same image, same bytes.
std::string encode_png_bgr(const unsigned char* bgr, int width, int height, std::size_t row_bytes);

}  // namespace conform
