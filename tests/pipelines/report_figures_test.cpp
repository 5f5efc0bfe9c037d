// The thinning the job reports use for glyphs and long lines: every k-th index and the last, the same every time.

#include "conform/pipelines/common/report_figures.h"

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(ReportFigures, SpreadIndicesKeepFirstAndLastWithinTheLimit) {
  EXPECT_TRUE(spread_indices(10, 0).empty());
  EXPECT_TRUE(spread_indices(0, 5).empty());
  EXPECT_EQ(spread_indices(5, 10), (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(spread_indices(10, 4), (std::vector<std::size_t>{0, 3, 6, 9}));  // step ceil(10 / 4) = 3
  EXPECT_EQ(spread_indices(11, 4), (std::vector<std::size_t>{0, 3, 6, 9, 10}));
  const std::vector<std::size_t> big = spread_indices(177427, 4000);
  EXPECT_LE(big.size(), 4001u);
  EXPECT_GE(big.size(), 3900u);
  EXPECT_EQ(big.front(), 0u);
  EXPECT_EQ(big.back(), 177426u);
}

TEST(ReportFigures, GlyphsPickTheSameRowsFromOriginsAndDirections) {
  std::vector<Eigen::Vector3d> at, direction;
  for (int i = 0; i < 9; ++i) at.emplace_back(i, 0, 0), direction.emplace_back(0, 0, i);
  const ReportGlyphs g = spread_glyphs(at, direction, 3);
  ASSERT_EQ(g.origins.size(), 4u);  // step 3: 0, 3, 6, and the last, 8
  ASSERT_EQ(g.directions.size(), g.origins.size());
  EXPECT_EQ(g.origins.back().x(), 8.0);
  for (std::size_t k = 0; k < g.origins.size(); ++k) EXPECT_EQ(g.origins[k].x(), g.directions[k].z());
  EXPECT_THROW(spread_glyphs(at, {}, 3), Error);
  EXPECT_EQ(row_numbers(3), (std::vector<double>{1.0, 2.0, 3.0}));
}

}  // namespace
}  // namespace conform
