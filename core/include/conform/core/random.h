#pragma once
// The one source of randomness (generators, RANSAC, sampling): a seeded xoshiro256** stream with its own uniform and normal
// draws, so that the same seed gives the same numbers with every compiler and standard library
// (std::normal_distribution and friends are implementation-defined).

#include <cstdint>

namespace conform {

class Random {
 public:
  // Independent streams from one seed: `stream` picks which (e.g. one for noise, one for outliers), so that turning
  // one effect on or off does not change the numbers another one draws.
  explicit Random(std::uint64_t seed, std::uint64_t stream = 0);

  // Next 64 random bits (xoshiro256**, Blackman & Vigna 2018).
  std::uint64_t next_u64();
  // Uniform in [0, 1), 53 random bits.
  double uniform();
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [0, n), without modulo bias; n > 0.
  std::uint64_t below(std::uint64_t n);
  // Standard normal (mean 0, standard deviation 1), Box-Muller transform; the second value of a pair is kept for
  // the next call.
  double normal();

 private:
  std::uint64_t s_[4];
  bool has_spare_ = false;
  double spare_ = 0.0;
};

}  // namespace conform
