#include "conform/core/radix_sort.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/random.h"

namespace conform {
namespace {

std::uint64_t bits_of(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Ground truth: std::sort, with -0 put before +0 (std::sort may leave the two in either order).
std::vector<double> sorted_by_std(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  for (std::size_t i = 0; i + 1 < values.size(); ++i) {
    if (values[i] == 0.0 && values[i + 1] == 0.0) {
      std::size_t j = i;
      while (j < values.size() && values[j] == 0.0) ++j;
      std::stable_partition(values.begin() + static_cast<std::ptrdiff_t>(i), values.begin() + static_cast<std::ptrdiff_t>(j),
                            [](double v) { return std::signbit(v); });
      i = j;
    }
  }
  return values;
}

void expect_bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(bits_of(a[i]), bits_of(b[i])) << "at " << i;
}

// Sizes on both sides of the small-list path, values of mixed signs and magnitudes (squared residuals, signed
// offsets, wide exponents), ties, zeros of both signs and infinities: the same bits in the same order as std::sort.
TEST(RadixSort, SameSequenceAsStdSort) {
  Random random(5);
  for (const std::size_t n : {0u, 1u, 2u, 17u, 255u, 256u, 257u, 1000u, 100000u}) {
    std::vector<double> values(n);
    for (double& v : values) {
      const double pick = random.uniform();
      if (pick < 0.4) {
        v = std::pow(random.normal(), 2.0) * 1e-3;  // squared residuals, mm^2
      } else if (pick < 0.7) {
        v = random.normal() * std::pow(10.0, random.uniform(-30.0, 30.0));
      } else if (pick < 0.8) {
        v = static_cast<double>(random.below(5)) - 2.0;  // ties
      } else if (pick < 0.9) {
        v = random.uniform() < 0.5 ? 0.0 : -0.0;
      } else {
        v = random.uniform() < 0.5 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::max();
      }
    }
    std::vector<double> radix = values;
    radix_sort(radix);
    expect_bitwise_equal(radix, sorted_by_std(values));
  }
}

// Every value alike: every pass skipped, the list unchanged.
TEST(RadixSort, AllEqualValuesStayPut) {
  std::vector<double> values(1000, 0.125);
  radix_sort(values);
  EXPECT_TRUE(std::all_of(values.begin(), values.end(), [](double v) { return v == 0.125; }));
}

// NaNs go to the ends, the numbers between them in order.
TEST(RadixSort, NaNsGoToTheEnds) {
  std::vector<double> values(600);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<double>((i * 7919) % 600) - 300.0;
  values[10] = std::numeric_limits<double>::quiet_NaN();
  values[20] = -std::numeric_limits<double>::quiet_NaN();
  radix_sort(values);
  EXPECT_TRUE(std::isnan(values.front()));
  EXPECT_TRUE(std::isnan(values.back()));
  EXPECT_TRUE(std::is_sorted(values.begin() + 1, values.end() - 1));
}

}  // namespace
}  // namespace conform
