#pragma once
// One loop over independent tasks on OpenMP's threads that keeps exceptions inside the parallel region (an exception
// that leaves one terminates the process): each task's is caught, and the first in index order is rethrown after the
// loop, so which error a caller sees does not depend on the number of threads or their timing.

#include <cstddef>
#include <exception>
#include <vector>

namespace conform {

// f(i) for every i < n, one i at a time a thread (dynamic schedule: tasks of uneven cost, such as ICP probes or the
// two sides of a feature match). Results written by f to slot i are the same for any number of threads.
template <typename F>
void for_each_in_parallel(std::size_t n, const F& f) {
  std::vector<std::exception_ptr> failed(n);
  const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(dynamic, 1) if (count > 1)
  for (std::ptrdiff_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    try {
      f(i);
    } catch (...) {
      failed[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : failed) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace conform
