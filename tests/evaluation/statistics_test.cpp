#include "conform/evaluation/statistics.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(Percentile, InterpolatesLinearlyBetweenClosestRanks) {
  const std::vector<double> v = {1, 2, 3, 4, 5};
  // rank = p / 100 * (n - 1): 5 % -> 0.2, 95 % -> 3.8, 99 % -> 3.96 (NumPy: percentile([1..5], 5) = 1.2).
  EXPECT_DOUBLE_EQ(percentile_of_sorted(v, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile_of_sorted(v, 5), 1.2);
  EXPECT_DOUBLE_EQ(percentile_of_sorted(v, 50), 3.0);
  EXPECT_DOUBLE_EQ(percentile_of_sorted(v, 95), 4.8);
  EXPECT_DOUBLE_EQ(percentile_of_sorted(v, 99), 4.96);
  EXPECT_DOUBLE_EQ(percentile_of_sorted(v, 100), 5.0);
  EXPECT_DOUBLE_EQ(percentile_of_sorted({7.5}, 95), 7.5);
  EXPECT_DOUBLE_EQ(percentile_of_sorted({0, 10}, 25), 2.5);
  EXPECT_DOUBLE_EQ(percentile_of_sorted({2, 2, 2, 9}, 50), 2.0);  // equal neighbours: exactly that value
  EXPECT_TRUE(std::isnan(percentile_of_sorted({}, 50)));
  EXPECT_THROW(percentile_of_sorted(v, 101), Error);
  EXPECT_THROW(percentile_of_sorted(v, -1), Error);
}

TEST(DeviationStatistics, KnownSetWithToleranceBand) {
  DeviationStatisticsOptions options;
  options.tolerance_mm = 1.0;
  const DeviationStatistics s = deviation_statistics({2, -1, 0, 1, -2}, options);
  EXPECT_EQ(s.count, 5u);
  EXPECT_EQ(s.excluded, 0u);
  EXPECT_EQ(s.min_mm, -2.0);
  EXPECT_EQ(s.max_mm, 2.0);
  EXPECT_EQ(s.mean_mm, 0.0);
  EXPECT_DOUBLE_EQ(s.std_mm, std::sqrt(2.0));  // population: sum of squares 10 over 5
  EXPECT_DOUBLE_EQ(s.rms_mm, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(s.mean_abs_mm, 1.2);
  EXPECT_DOUBLE_EQ(s.p5_mm, -1.8);
  EXPECT_DOUBLE_EQ(s.p50_mm, 0.0);
  EXPECT_DOUBLE_EQ(s.p95_mm, 1.8);
  EXPECT_DOUBLE_EQ(s.p99_mm, 1.96);
  EXPECT_DOUBLE_EQ(s.p95_abs_mm, 2.0);  // |d| sorted: 0 1 1 2 2, rank 3.8
  // The band is closed: -1 and 1 are inside.
  EXPECT_DOUBLE_EQ(s.in_tolerance_pct, 60.0);
  EXPECT_DOUBLE_EQ(s.above_pct, 20.0);
  EXPECT_DOUBLE_EQ(s.below_pct, 20.0);
  EXPECT_FALSE(s.within_tolerance());
}

TEST(DeviationStatistics, MeanStdAndRmsOfAnOffsetSet) {
  // 0.1 + k * 1e-3 for k = 0..999: mean 0.5995, population std sqrt((n^2 - 1) / 12) * 1e-3.
  std::vector<double> v;
  for (int k = 0; k < 1000; ++k) v.push_back(0.1 + k * 1e-3);
  const DeviationStatistics s = deviation_statistics(v);
  EXPECT_NEAR(s.mean_mm, 0.5995, 1e-14);
  const double std_expected = std::sqrt((1000.0 * 1000.0 - 1.0) / 12.0) * 1e-3;
  EXPECT_NEAR(s.std_mm, std_expected, 1e-14);
  EXPECT_NEAR(s.rms_mm, std::sqrt(s.mean_mm * s.mean_mm + std_expected * std_expected), 1e-14);
  EXPECT_FALSE(s.tolerance_mm.has_value());
  EXPECT_FALSE(s.within_tolerance());
}

TEST(DeviationStatistics, NaNsAreExcludedAndAnAllInsideSetIsWithinTolerance) {
  DeviationStatisticsOptions options;
  options.tolerance_mm = 0.5;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const DeviationStatistics s = deviation_statistics({0.1, nan, -0.5, 0.5, nan}, options);
  EXPECT_EQ(s.count, 3u);
  EXPECT_EQ(s.excluded, 2u);
  EXPECT_EQ(s.in_tolerance_pct, 100.0);
  EXPECT_TRUE(s.within_tolerance());
  const DeviationStatistics none = deviation_statistics({nan}, options);
  EXPECT_EQ(none.count, 0u);
  EXPECT_TRUE(std::isnan(none.mean_mm));
  EXPECT_FALSE(none.within_tolerance());
}

TEST(DeviationStatistics, RejectsInfiniteValuesAndBadTolerances) {
  EXPECT_THROW(deviation_statistics({1.0, std::numeric_limits<double>::infinity()}), Error);
  for (double t : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    DeviationStatisticsOptions options;
    options.tolerance_mm = t;
    std::string why;
    EXPECT_FALSE(options.IsValid(&why));
    EXPECT_NE(why.find("tolerance"), std::string::npos);
    EXPECT_THROW(deviation_statistics({1.0}, options), Error);
  }
}

}  // namespace
}  // namespace conform
