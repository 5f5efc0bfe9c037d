// The eroded-blade generator: craters of the asked depth and radius along the normal, noise of the asked size,
// rims on the reference, the same numbers for the same seed.

#include "conform/datasets/eroded.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

TEST(Eroded, CraterDepthRimAndNoise) {
  ErodedOptions o;
  o.rows = 21, o.cols = 31, o.length_mm = 60.0, o.width_mm = 40.0;
  o.craters = {Crater{0.0, 0.0, 10.0, 1.5}};
  o.noise_mm = 0.0;
  const ErodedScan clean = generate_eroded(o);
  ASSERT_EQ(clean.eroded.size(), 21u * 31u);
  // The grid's centre node (row 10, col 15) is the crater's centre: exactly D below the reference along the normal.
  const std::size_t centre = 10 * 31 + 15;
  EXPECT_NEAR((clean.reference[centre] - clean.eroded[centre]).norm(), 1.5, 1e-12);
  EXPECT_NEAR((clean.reference[centre] - clean.eroded[centre]).dot(blade_normal(o, 0, 0)), 1.5, 1e-12);
  EXPECT_EQ(clean.reference[0], clean.eroded[0]);  // outside the crater: untouched
  ASSERT_EQ(clean.rims.size(), 1u);
  for (const Eigen::Vector3d& p : clean.rims[0]) {
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 10.0, 1e-12);
    EXPECT_NEAR(p.z(), blade_point(o, p.x(), p.y()).z(), 1e-12);
  }
  EXPECT_DOUBLE_EQ(crater_depth(o, 5.0, 0.0), 1.5 * std::pow(1.0 - 0.25, 3));
  o.noise_mm = 0.02;
  const ErodedScan noisy = generate_eroded(o);
  double sum2 = 0.0;
  for (std::size_t i = 0; i < noisy.eroded.size(); ++i) sum2 += std::pow(noisy.eroded[i].z() - clean.eroded[i].z(), 2);
  EXPECT_NEAR(std::sqrt(sum2 / static_cast<double>(noisy.eroded.size())), 0.02, 0.002);  // 651 samples: ~3 % scatter
  EXPECT_EQ(generate_eroded(o).eroded, noisy.eroded);  // same seed, same numbers
  o.seed = 2;
  EXPECT_NE(generate_eroded(o).eroded, noisy.eroded);
}

TEST(Eroded, RingsLipsBumpsAndReferenceBias) {
  ErodedOptions o;
  o.rows = 41, o.cols = 41, o.length_mm = 80.0, o.width_mm = 80.0;  // 2 mm grid, node (20, 20) at the origin
  o.noise_mm = 0.0;
  o.craters = {Crater{0.0, 0.0, 20.0, 1.5, 8.0, 0.0, 0.0}, Crater{-30.0, -30.0, 6.0, 1.0, 0.0, 0.4, 4.0}};
  o.bumps = {Bump{30.0, 30.0, 5.0, 2.0}};
  EXPECT_EQ(crater_depth(o, 0.0, 0.0), 0.0);                // the ring's hole
  EXPECT_DOUBLE_EQ(crater_depth(o, 14.0, 0.0), 1.5);        // its middle, (8 + 20) / 2
  EXPECT_DOUBLE_EQ(crater_depth(o, 0.0, -11.0), 1.5 * std::pow(1.0 - 0.25, 3));  // 3 mm off the middle, h = 6
  EXPECT_DOUBLE_EQ(raised_height(o, -30.0, -22.0), 0.4);    // the lip's crest at a + w / 2
  EXPECT_EQ(raised_height(o, -30.0, -20.0), 0.0);           // beyond the lip
  EXPECT_DOUBLE_EQ(raised_height(o, 30.0, 30.0), 2.0);      // the bump's top
  o.reference_offset_mm = 0.3;
  o.reference_tilt_deg = 1.0;
  const ErodedScan scan = generate_eroded(o);
  const std::size_t k = 20 * 41 + 30;  // x = 20, y = 0
  EXPECT_NEAR(scan.reference[k].z(), blade_point(o, 20.0, 0.0).z() + 0.3 + std::tan(M_PI / 180.0) * 20.0, 1e-12);
  const std::size_t bump = 35 * 41 + 35;  // x = y = 30
  EXPECT_NEAR((scan.eroded[bump] - blade_point(o, 30.0, 30.0)).dot(blade_normal(o, 30.0, 30.0)), 2.0, 1e-12);
  o.craters = {Crater{0.0, 0.0, 10.0, 1.0, 10.0}};  // inner radius = radius
  EXPECT_THROW(generate_eroded(o), Error);
  o.craters = {Crater{0.0, 0.0, 10.0, 1.0, 0.0, 0.5, 0.0}};  // a lip without a width
  EXPECT_THROW(generate_eroded(o), Error);
}

TEST(Eroded, RejectsBadOptions) {
  ErodedOptions o;
  o.craters = {Crater{0.0, 0.0, 4.0, 3.0}};  // deeper than half its radius
  EXPECT_THROW(generate_eroded(o), Error);
  o = ErodedOptions{};
  o.rows = 2;
  EXPECT_THROW(generate_eroded(o), Error);
}

}  // namespace
}  // namespace conform
