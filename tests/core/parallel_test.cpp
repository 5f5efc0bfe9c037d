// for_each_in_parallel (core/parallel.h): every task runs once, whatever the number of threads; the first failure in
// index order is the one rethrown, after every task has run.

#include "conform/core/parallel.h"

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

namespace conform {
namespace {

TEST(ForEachInParallel, RunsEveryTaskOnceForAnyNumberOfThreads) {
  const int before = omp_get_max_threads();
  for (const int threads : {1, 2, 4}) {
    omp_set_num_threads(threads);
    std::vector<int> runs(1000, 0);
    for_each_in_parallel(runs.size(), [&](std::size_t i) { runs[i] += static_cast<int>(i % 7) + 1; });
    for (std::size_t i = 0; i < runs.size(); ++i) ASSERT_EQ(runs[i], static_cast<int>(i % 7) + 1) << i;
  }
  omp_set_num_threads(before);
  int never = 0;
  for_each_in_parallel(0, [&](std::size_t) { ++never; });
  EXPECT_EQ(never, 0);
}

TEST(ForEachInParallel, TheFirstFailureInIndexOrderIsRethrownAfterEveryTask) {
  const int before = omp_get_max_threads();
  for (const int threads : {1, 2, 4}) {
    omp_set_num_threads(threads);
    std::atomic<int> ran{0};
    try {
      for_each_in_parallel(200, [&](std::size_t i) {
        ++ran;
        if (i == 150 || i == 37 || i == 90) throw std::runtime_error("task " + std::to_string(i));
      });
      FAIL() << "nothing was rethrown";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "task 37");
    }
    EXPECT_EQ(ran.load(), 200);
  }
  omp_set_num_threads(before);
}

}  // namespace
}  // namespace conform
