// Eq. (5) generalised: any table of (phi, alpha) rows, linear, quadratic or periodic-spline interpolation, with the
// paper's conventions checked (a 360 deg row closes the table), and impossible tables rejected.

#include "conform/toolpath/intersection/groove_table.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/constants.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

TEST(GrooveTable, QuartersAreTheFourRowTable) {
  const GrooveTable q = GrooveTable::quarters(0.1, 0.5, 0.3, 0.5, GrooveInterpolation::kLinear);
  std::string why;
  ASSERT_TRUE(q.IsValid(&why)) << why;
  EXPECT_NEAR(q.at(0.0), 0.1, 1e-15);
  EXPECT_NEAR(q.at(kPi / 4), 0.3, 1e-15);              // half way toe -> side
  EXPECT_NEAR(q.at(-kPi / 4), 0.3, 1e-15);             // half way side -> toe, cyclic
  EXPECT_NEAR(q.at(2.0 * kPi + kPi / 2), 0.5, 1e-15);  // wrapped
}

TEST(GrooveTable, AnyRowsLinearlyWithTheClosingRow) {
  // Uneven rows and the paper's closing row at 360 deg with the toe's angle.
  const GrooveTable t({{0.0, 30 * kDeg}, {40 * kDeg, 50 * kDeg}, {200 * kDeg, 20 * kDeg}, {2 * kPi, 30 * kDeg}},
                      GrooveInterpolation::kLinear);
  std::string why;
  ASSERT_TRUE(t.IsValid(&why)) << why;
  EXPECT_NEAR(t.at(20 * kDeg), 40 * kDeg, 1e-12);
  EXPECT_NEAR(t.at(120 * kDeg), 35 * kDeg, 1e-12);
  EXPECT_NEAR(t.at(280 * kDeg), 25 * kDeg, 1e-12);
  EXPECT_NEAR(t.at(359.999999 * kDeg), 30 * kDeg, 1e-7);
}

// The periodic spline passes through every row and is C1 across 360 deg; on rows of a pure cos it stays within a
// few hundredths of a degree of it (the cubic spline's error on 12 rows).
TEST(GrooveTable, PeriodicSplineInterpolatesTheRowsSmoothlyAcrossTheToe) {
  std::vector<std::pair<double, double>> rows;
  const auto alpha = [](double phi) { return (30.0 + 10.0 * std::cos(phi)) * kDeg; };
  for (int i = 0; i < 12; ++i) rows.emplace_back(i * 30 * kDeg, alpha(i * 30 * kDeg));
  const GrooveTable s(rows, GrooveInterpolation::kSpline);
  std::string why;
  ASSERT_TRUE(s.IsValid(&why)) << why;
  for (const auto& [phi, a] : rows) EXPECT_NEAR(s.at(phi), a, 1e-12);
  double worst = 0.0;
  for (int k = 0; k < 3600; ++k) worst = std::max(worst, std::abs(s.at(k * 0.1 * kDeg) - alpha(k * 0.1 * kDeg)));
  EXPECT_LT(worst, 0.05 * kDeg);
  const double h = 1e-6;
  const double slope_before = (s.at(2 * kPi - h) - s.at(2 * kPi - 2 * h)) / h;
  const double slope_after = (s.at(h) - s.at(0.0)) / h;
  EXPECT_NEAR(slope_before, slope_after, 1e-4);
}

TEST(GrooveTable, ImpossibleTablesAreInvalid) {
  std::string why;
  EXPECT_FALSE(GrooveTable({{0.0, -5 * kDeg}}, GrooveInterpolation::kLinear).IsValid(&why));
  EXPECT_NE(why.find("negative"), std::string::npos) << why;
  EXPECT_FALSE(GrooveTable({{0.0, 95 * kDeg}}, GrooveInterpolation::kLinear).IsValid(&why));
  EXPECT_FALSE(GrooveTable({{0.0, 0.1}, {1.0, 0.2}, {1.0, 0.3}}, GrooveInterpolation::kLinear).IsValid(&why));
  EXPECT_NE(why.find("increase"), std::string::npos) << why;
  EXPECT_FALSE(GrooveTable({{0.0, 0.1}, {2 * kPi, 0.3}}, GrooveInterpolation::kLinear).IsValid(&why));
  EXPECT_NE(why.find("close"), std::string::npos) << why;
  EXPECT_FALSE(GrooveTable({{0.0, 0.1}, {4.0, 0.2}}, GrooveInterpolation::kSpline).IsValid(&why));
  EXPECT_FALSE(GrooveTable({}, GrooveInterpolation::kLinear).IsValid(&why));
  // A spline through steep rows overshoots below 0 deg between them.
  EXPECT_FALSE(
      GrooveTable({{0.0, 0.0}, {0.3, 1.4}, {0.6, 0.0}, {3.0, 0.0}}, GrooveInterpolation::kSpline).IsValid(&why));
  EXPECT_NE(why.find("overshoots"), std::string::npos) << why;
}

}  // namespace
}  // namespace conform
