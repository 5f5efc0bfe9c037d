#include "conform/core/radix_sort.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

namespace conform {

namespace {

constexpr int kRadixBits = 8;
constexpr int kRadixPasses = 64 / kRadixBits;
constexpr std::size_t kRadixBuckets = std::size_t{1} << kRadixBits;
// Below this many values std::sort is faster than the histograms' set-up.
constexpr std::size_t kRadixSmall = 256;

// The value's bits turned so that unsigned order is the numbers' order: a positive value's sign bit set, a negative
// value's bits all flipped (larger magnitude, smaller key).
std::uint64_t radix_key(double value) {
  std::uint64_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return (bits >> 63) != 0 ? ~bits : bits | (std::uint64_t{1} << 63);
}

double radix_value(std::uint64_t key) {
  const std::uint64_t bits = (key >> 63) != 0 ? key & ~(std::uint64_t{1} << 63) : ~key;
  double value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace

void radix_sort(std::vector<double>& values) {
  const std::size_t n = values.size();
  if (n < kRadixSmall) {
    std::vector<std::uint64_t> keys(n);
    for (std::size_t i = 0; i < n; ++i) keys[i] = radix_key(values[i]);
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < n; ++i) values[i] = radix_value(keys[i]);
    return;
  }
  std::vector<std::uint64_t> keys(n), scratch(n);
  std::array<std::array<std::size_t, kRadixBuckets>, kRadixPasses> counts{};
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = radix_key(values[i]);
    keys[i] = k;
    for (int d = 0; d < kRadixPasses; ++d) ++counts[d][(k >> (d * kRadixBits)) & (kRadixBuckets - 1)];
  }
  for (int d = 0; d < kRadixPasses; ++d) {
    std::array<std::size_t, kRadixBuckets>& count = counts[d];
    if (std::find(count.begin(), count.end(), n) != count.end()) continue;  // one digit for all: nothing moves
    std::size_t start = 0;
    for (std::size_t& c : count) {
      const std::size_t here = c;
      c = start;
      start += here;
    }
    for (const std::uint64_t k : keys) scratch[count[(k >> (d * kRadixBits)) & (kRadixBuckets - 1)]++] = k;
    keys.swap(scratch);
  }
  for (std::size_t i = 0; i < n; ++i) values[i] = radix_value(keys[i]);
}

}  // namespace conform
