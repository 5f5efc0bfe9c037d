#pragma once
// Timing for benchmarks: the best of several runs, in seconds, by the wall clock or by the calling thread's CPU time.

#include <algorithm>
#include <chrono>
#include <limits>

#include <time.h>

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

// CPU time of the calling thread: steadier than wall-clock time for single-threaded work on a machine shared with
// other jobs (their time slices do not count).
template <typename Fn>
double best_cpu_seconds(int repeats, Fn&& fn) {
  const auto now = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < repeats; ++i) {
    const double start = now();
    fn();
    best = std::min(best, now() - start);
  }
  return best;
}

}  // namespace conform::bench
