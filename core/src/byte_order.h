#pragma once
// Loading and storing binary scalars of a given byte order, for the binary PLY and STL readers and writers.
// memcpy (not pointer casts) because file data has no alignment; compilers turn it into a plain load.

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace conform::detail {

constexpr bool kHostIsLittleEndian = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;

template <typename T>
T byte_swapped(T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) {
    const unsigned char t = bytes[i];
    bytes[i] = bytes[sizeof(T) - 1 - i];
    bytes[sizeof(T) - 1 - i] = t;
  }
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

// A T stored at `src` in the file's byte order (`little_endian` or big).
template <typename T>
T load(const char* src, bool little_endian) {
  T value;
  std::memcpy(&value, src, sizeof(T));
  return little_endian == kHostIsLittleEndian ? value : byte_swapped(value);
}

// Stores `value` at `dst` in little-endian order (what conform writes).
template <typename T>
void store_le(char* dst, T value) {
  if (!kHostIsLittleEndian) value = byte_swapped(value);
  std::memcpy(dst, &value, sizeof(T));
}

}  // namespace conform::detail
