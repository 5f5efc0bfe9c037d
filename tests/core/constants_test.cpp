// The shared constants and the median (core/constants.h, core/median.h) against their definitions.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "conform/core/constants.h"
#include "conform/core/median.h"

namespace conform {
namespace {

TEST(Constants, AnglesConvertExactlyWhereTheDefinitionIsExact) {
  EXPECT_EQ(kHalfPi, std::acos(0.0));
  EXPECT_EQ(radians(180.0), kPi);
  EXPECT_EQ(radians(90.0), kHalfPi);
  EXPECT_EQ(radians(0.0), 0.0);
  EXPECT_NEAR(radians(1.0) * kDegPerRad, 1.0, 1e-15);
  EXPECT_NEAR(kPi * kDegPerRad, 180.0, 1e-12);
  EXPECT_NEAR(radians(-45.0), -std::atan(1.0), 1e-16);
}

TEST(Constants, NaNIsNotANumber) {
  EXPECT_TRUE(std::isnan(kNaN));
}

TEST(Median, OddCountGivesTheMiddleValue) {
  EXPECT_EQ(median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_EQ(median({2.0}), 2.0);
}

TEST(Median, EvenCountGivesTheUpperOfTheTwoMiddleValues) {
  EXPECT_EQ(median({4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_EQ(median({-1.0, -2.0}), -1.0);
}

TEST(Median, EmptyGivesZeroAndTheInputIsNotReordered) {
  EXPECT_EQ(median({}), 0.0);
  const std::vector<double> values{9.0, 7.0, 8.0};
  EXPECT_EQ(median(values), 8.0);
  EXPECT_EQ(values, (std::vector<double>{9.0, 7.0, 8.0}));
}

}  // namespace
}  // namespace conform
