// The deviation to the smooth surface beside a rim, where a flat cap meets a curved side at a crease: the cap's
// tessellation is the polygon inscribed in its curved outline, and the sliver between the polygon's chords and the
// outline is cap too. A block 60 x 40 x 20 mm with R10 fillets on its vertical edges (test::filleted_block), points
// over that sliver at known signed offsets from the cap: outside the part they read +h (they read -h when the curved
// side measured them and its normal signed them: 130 points of an exported 8 mm STL), inside never positive.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/evaluation/deviation.h"
#include "test_meshes.h"

namespace conform {
namespace {

using V = Eigen::Vector3d;

constexpr double kSizeX = 60.0, kSizeY = 40.0, kHeight = 20.0, kRadius = 10.0;

struct RimPoint {
  V point;
  double truth_mm;  // signed distance to the exact block, + outside
};

// Points over the sliver of the caps at z = 0 and z = kHeight: on a fillet's outline between its chord and its arc
// (a share u in [0.05, 0.95] of the way), offset by h along the cap's outward normal. The truth: +h outside (the
// cap is nearest); inside, -min(|h|, distance to the side).
std::vector<RimPoint> sliver_points(int chords, double h, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double hx = kSizeX / 2 - kRadius, hy = kSizeY / 2 - kRadius;
  const double cx[4] = {hx, -hx, -hx, hx}, cy[4] = {hy, hy, -hy, -hy};
  const double step = kPi / 2 / chords;
  std::vector<RimPoint> out;
  for (int i = 0; i < 400; ++i) {
    const int c = i % 4;
    const int k = static_cast<int>(unit(rng) * chords);
    const double a0 = kPi / 2 * c + step * k;
    const double a = a0 + step * (0.02 + 0.96 * unit(rng));
    // The chord from a0 to a0 + step is at kRadius cos(step / 2) from the centre at its middle.
    const double chord_r = kRadius * std::cos(step / 2) / std::cos(a - a0 - step / 2);
    const double r = chord_r + (0.05 + 0.9 * unit(rng)) * (kRadius - chord_r);
    const bool top = i % 8 >= 4;
    const double z = top ? kHeight + h : -h;
    const V p(cx[c] + r * std::cos(a), cy[c] + r * std::sin(a), z);
    const double side = test::filleted_block_side_distance(kSizeX, kSizeY, kRadius, V(p.x(), p.y(), 0.0));
    out.push_back({p, h >= 0.0 ? h : -std::min(-h, -side)});
  }
  return out;
}

// 4 chords a fillet (3.9 mm chords, 0.19 mm sagitta: a coarse STL; with 2 the 45 deg between chords is a crease and
// the fillet is measured to its facets) and 16 (0.98 mm, 0.012 mm).
TEST(RimDeviation, PointsOverACapsSliverTakeTheCapsSign) {
  for (int chords : {4, 16}) {
    const Mesh block = test::filleted_block(kSizeX, kSizeY, kHeight, kRadius, chords);
    std::mt19937_64 rng(11);
    int wrong = 0, points = 0;
    double worst_outside = 0.0, worst_inside = 0.0, worst_on = 0.0;
    for (double h : {0.1, 0.02, 0.0, -0.02, -0.1}) {
      const std::vector<RimPoint> sample = sliver_points(chords, h, rng);
      std::vector<V> scan;
      for (const RimPoint& p : sample) scan.push_back(p.point);
      const DeviationResult d = compute_deviation(scan, block);
      for (std::size_t i = 0; i < sample.size(); ++i) {
        const double got = d.deviation_mm[i], truth = sample[i].truth_mm, error = std::abs(got - truth);
        ++points;
        if ((truth > 0.0 && got < 0.0) || (truth < 0.0 && got > 0.0)) ++wrong;
        double& worst = h > 0.0 ? worst_outside : h < 0.0 ? worst_inside : worst_on;
        worst = std::max(worst, error);
      }
    }
    std::printf(
        "%2d chords a fillet: %d of %d points with the wrong sign; |error| outside %.3g, on the cap %.3g, "
        "inside %.3g mm\n",
        chords, wrong, points, worst_outside, worst_on, worst_inside);
    EXPECT_EQ(wrong, 0) << chords;
    // Outside and on the cap the plane is measured: exact. Inside, the side when it is nearer than the cap, within
    // the smooth surface's error on a circle (Phong tessellation is exact to second order): 0.0055 mm measured at 4
    // chords (3 % of the sagitta), 2.2e-5 at 16. Before: 732 and 752 of 2000 signs wrong, outside up to 0.30 and
    // 0.20 mm off.
    EXPECT_LT(worst_outside, 1e-9) << chords;
    EXPECT_LT(worst_on, 1e-9) << chords;
    EXPECT_LT(worst_inside, chords == 4 ? 0.01 : 1e-4) << chords;
  }
}

// Over the cap's polygon itself, away from the sliver, and on the flat sides, nothing changes: the plane's distance.
TEST(RimDeviation, FlatFacesStayFlat) {
  const Mesh block = test::filleted_block(kSizeX, kSizeY, kHeight, kRadius, 2);
  std::vector<V> scan;
  std::vector<double> truth;
  for (double h : {0.1, -0.1}) {
    for (double x : {-25.0, 0.0, 17.0}) {
      scan.emplace_back(x, 3.0, -h);  // bottom cap
      truth.push_back(h);
      scan.emplace_back(x, -4.0, kHeight + h);  // top cap
      truth.push_back(h);
      scan.emplace_back(x / 2, kSizeY / 2 + h, 10.0);  // flat side between the fillets
      truth.push_back(h);
    }
  }
  const DeviationResult d = compute_deviation(scan, block);
  for (std::size_t i = 0; i < scan.size(); ++i) EXPECT_NEAR(d.deviation_mm[i], truth[i], 1e-12) << i;
}

}  // namespace
}  // namespace conform
