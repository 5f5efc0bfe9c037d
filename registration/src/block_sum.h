#pragma once
// Parallel sums that give the same bits for any number of threads: [0, n) is cut into blocks of a fixed size, each
// block is summed in order by one thread, and the block sums are added in block order.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace conform::detail {

inline constexpr std::size_t kSumBlock = 4096;
// Fewer items than this are summed by the calling thread alone (the same blocks, so the same bits): a parallel region
// wakes the team, and libgomp's idle threads then spin for a while, taking a core from the serial code that follows.
inline constexpr std::size_t kParallelFrom = 32768;

// add(i, acc) adds item i to acc; Acc needs a copy constructor and operator+=.
template <typename Acc, typename Add>
Acc block_sum(std::size_t n, const Acc& zero, Add&& add) {
  const std::size_t blocks = (n + kSumBlock - 1) / kSumBlock;
  std::vector<Acc, Eigen::aligned_allocator<Acc>> partial(blocks, zero);
  const auto count = static_cast<std::ptrdiff_t>(blocks);
#pragma omp parallel for schedule(static) if (n >= kParallelFrom)
  for (std::ptrdiff_t b = 0; b < count; ++b) {
    Acc acc = zero;
    const std::size_t begin = static_cast<std::size_t>(b) * kSumBlock;
    const std::size_t end = begin + kSumBlock < n ? begin + kSumBlock : n;
    for (std::size_t i = begin; i < end; ++i) add(i, acc);
    partial[static_cast<std::size_t>(b)] = acc;
  }
  Acc total = zero;
  for (const Acc& p : partial) total += p;
  return total;
}

}  // namespace conform::detail
