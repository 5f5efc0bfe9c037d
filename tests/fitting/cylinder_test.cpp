// The cylinder fit on generated tube scans (50k points, fixed seeds) against the generator's truth: the figures of
// issue 4's "What must be shown". Each case prints its figures ([figures] lines) so that a run shows the margins.

#include "conform/fitting/cylinder.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tube_fit.h"

namespace conform {
namespace {

using test::fit_generated;
using test::FittedScan;
using test::kDeg;
using test::print_figures;
using test::tube_scan_options;

// The bounds of the issue for sigma 0.2 mm.
constexpr double kRadiusBound = 0.01;  // mm
constexpr double kAngleBound = 0.005;  // deg
constexpr double kOffsetBound = 0.02;  // mm

void expect_tight(const FittedScan& f) {
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  EXPECT_TRUE(f.fit.converged);
  EXPECT_LE(std::abs(f.error.radius_mm), kRadiusBound);
  EXPECT_LE(f.error.angle_deg, kAngleBound);
  EXPECT_LE(f.error.offset_mm, kOffsetBound);
  // The covariance must explain the error it claims to bound (4 sigma).
  EXPECT_LE(std::abs(f.error.radius_mm), 4.0 * f.fit.radius_std_mm);
}

TEST(CylinderFit, FullTubeSigma02) {
  const FittedScan f = fit_generated(tube_scan_options(360.0, 0.2));
  print_figures("full tube, sigma 0.2", f);
  expect_tight(f);
  EXPECT_NEAR(f.fit.noise_sigma_mm, 0.2, 0.01);
  EXPECT_NEAR(f.fit.arc_rad, 2.0 * kPi, 1.0 * kDeg);
  EXPECT_EQ(f.fit.side, CylinderSide::kOuter);
  EXPECT_GT(f.fit.inlier_fraction, 0.99);
}

TEST(CylinderFit, Patch90DegSigma02) {
  const FittedScan f = fit_generated(tube_scan_options(90.0, 0.2));
  print_figures("90 deg patch, sigma 0.2", f);
  expect_tight(f);
  EXPECT_NEAR(f.fit.arc_rad, 90.0 * kDeg, 1.0 * kDeg);
}

TEST(CylinderFit, Patch180DegSigma2HasNoNoiseBias) {
  const FittedScan f = fit_generated(tube_scan_options(180.0, 2.0));
  print_figures("180 deg patch, sigma 2", f);
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  EXPECT_LE(std::abs(f.error.radius_mm), 0.1);
  EXPECT_LE(std::abs(f.error.radius_mm), 4.0 * f.fit.radius_std_mm);
  EXPECT_NEAR(f.fit.noise_sigma_mm, 2.0, 0.1);
}

TEST(CylinderFit, TwentyPercentOutliersKeepTheBounds) {
  for (double arc_deg : {360.0, 90.0}) {
    TubeOptions tube = tube_scan_options(arc_deg, 0.2);
    tube.outlier_fraction = 0.2;
    const FittedScan f = fit_generated(tube);
    print_figures(arc_deg > 180.0 ? "full tube, sigma 0.2, 20% outliers" : "90 deg patch, sigma 0.2, 20% outliers", f);
    expect_tight(f);
    EXPECT_NEAR(f.fit.inlier_fraction, 0.8, 0.01);
  }
}

TEST(CylinderFit, OvalTubeGivesTheMeanRadius) {
  TubeOptions tube = tube_scan_options(360.0, 0.2);
  tube.ovality_mm = 2.0;  // D_max - D_min = 8 mm
  const FittedScan f = fit_generated(tube);
  print_figures("oval full tube (a = 2 mm), sigma 0.2", f);
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  // a cos 2(theta - theta0) averages to zero over the turn: the mean radius is R.
  EXPECT_LE(std::abs(f.error.radius_mm), 0.1);
  EXPECT_GT(f.fit.inlier_fraction, 0.99);  // the ovality is shape, not outliers
}

}  // namespace
}  // namespace conform
