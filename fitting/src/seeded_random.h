#pragma once
// The fitting module's one source of randomness: SplitMix64 (Steele, Lea & Flood 2014) from the seed in the caller's
// Options, with bounded integers by rejection (Lemire 2019 without the fast path), so that the same seed draws the same
// numbers with every compiler and standard library (std::uniform_int_distribution is implementation-defined).

#include <cstdint>

namespace conform::detail {

class SeededRandom {
 public:
  explicit SeededRandom(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next_u64() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, n), n > 0, without modulo bias.
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = (0 - n) % n;  // 2^64 mod n: draws below it would favour small values
    for (;;) {
      const std::uint64_t x = next_u64();
      if (x >= limit) return x % n;
    }
  }

 private:
  std::uint64_t state_;
};

}  // namespace conform::detail
