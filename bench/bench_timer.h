#pragma once
// Wall-clock timing for benchmarks: the best of several runs, in seconds.

#include <algorithm>
#include <chrono>
#include <limits>

namespace conform::bench {

template <typename Fn>
double best_seconds(int repeats, Fn&& fn) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    best = std::min(best, elapsed.count());
  }
  return best;
}

}  // namespace conform::bench
