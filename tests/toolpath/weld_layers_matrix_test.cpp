// Weld layers over realistic variation (issue 17), on generated blades with ground truth (datasets/eroded.h): one to
// four craters, at the border, overlapping, ring-shaped, shallow, deep on a tightly curved blade, lips and bumps,
// noise 0 to 0.1 mm, grids 0.2 to 4 mm, a reference offset or tilted. Each plan either
//   - is ok, and layer 1 comes within dc/2 of >= 90 % of the true damage (nodes deeper than the threshold by the
//     generator's crater depth), every layer-1 point and chord midpoint lies within the chord error (+ 4 noise sigmas
//     + 0.02 mm of spline error) of the true eroded surface, and neighbouring layer-1 paths are dc apart within 25 %;
//   - or is not ok with the message that says why.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/datasets/eroded.h"
#include "conform/toolpath/weld/weld_layers.h"

namespace conform {
namespace {

struct Case {
  ErodedOptions blade;
  WeldLayerOptions weld;
};

Case base_case(double noise_mm) {
  Case c;
  c.blade.noise_mm = noise_mm;  // 120 x 80 mm, 2 mm grid, R 150 / 400 mm, twist
  c.weld.bead_spacing_mm = 3.0;
  c.weld.layer_height_mm = 1.0;
  c.weld.chord_error_mm = 0.05;
  c.weld.torch_distance_mm = 0.0;  // g = dc: the spacing check below is against dc itself
  return c;
}

// The true eroded surface: the blade pressed in by the craters, raised by lips and bumps.
Eigen::Vector3d true_eroded(const ErodedOptions& o, double x, double y) {
  return blade_point(o, x, y) - (crater_depth(o, x, y) - raised_height(o, x, y)) * blade_normal(o, x, y);
}

// Distance of p from the true eroded surface, along the normal, at the surface point with p's (x, y).
double off_surface(const ErodedOptions& o, const Eigen::Vector3d& p) {
  Eigen::Vector2d q(p.x(), p.y());
  for (int it = 0; it < 20; ++it) q -= true_eroded(o, q.x(), q.y()).head<2>() - p.head<2>();
  return std::abs((p - true_eroded(o, q.x(), q.y())).dot(blade_normal(o, q.x(), q.y())));
}

WeldLayerResult plan(const Case& c) {
  const ErodedScan scan = generate_eroded(c.blade);
  return plan_weld_layers(BezierNetwork(SurfaceGrid{scan.rows, scan.cols, scan.eroded}),
                          BezierNetwork(SurfaceGrid{scan.rows, scan.cols, scan.reference}), c.weld);
}

void expect_refilled(const Case& c, const WeldLayerResult& r, double spacing_error_pct = 25.0) {
  ASSERT_TRUE(r.ok) << r.termination;
  const ErodedOptions& o = c.blade;
  const double dc = c.weld.bead_spacing_mm;
  std::vector<const WeldPath*> layer1;
  for (const WeldPath& p : r.paths) {
    if (p.layer == 1) layer1.push_back(&p);
  }
  ASSERT_FALSE(layer1.empty());
  // Coverage of the true damage.
  std::vector<Eigen::Vector3d> dense;
  for (const WeldPath* p : layer1) {
    for (std::size_t i = 0; i + 1 < p->points.size(); ++i) {
      for (int k = 0; k < 16; ++k) dense.push_back(p->points[i] + (p->points[i + 1] - p->points[i]) * (k / 16.0));
    }
    dense.push_back(p->points.back());
  }
  std::size_t damaged = 0, covered = 0;
  for (int row = 0; row < o.rows; ++row) {
    for (int col = 0; col < o.cols; ++col) {
      const double x = -0.5 * o.length_mm + o.length_mm * col / (o.cols - 1);
      const double y = -0.5 * o.width_mm + o.width_mm * row / (o.rows - 1);
      if (!(crater_depth(o, x, y) > r.depth_threshold_mm + 4.0 * o.noise_mm)) continue;
      ++damaged;
      const Eigen::Vector3d node = true_eroded(o, x, y);
      double nearest = 1e9;
      for (const Eigen::Vector3d& q : dense) nearest = std::min(nearest, (q - node).norm());
      covered += nearest <= 0.5 * dc + 4.0 * o.noise_mm;
    }
  }
  ASSERT_GT(damaged, 0u);
  EXPECT_GE(100.0 * double(covered) / double(damaged), 90.0) << covered << " of " << damaged;
  // On the true surface within the chord error (points and chord midpoints).
  const double tolerance = c.weld.chord_error_mm + 4.0 * o.noise_mm + 0.02;
  double worst = 0.0;
  for (const WeldPath* p : layer1) {
    for (std::size_t i = 0; i < p->points.size(); ++i) {
      worst = std::max(worst, off_surface(o, p->points[i]));
      if (i + 1 < p->points.size()) worst = std::max(worst, off_surface(o, 0.5 * (p->points[i] + p->points[i + 1])));
    }
  }
  EXPECT_LE(worst, tolerance);
  // Spacing: an interior point of a layer-1 path is at least 0.75 dc from every other layer-1 path of its crater.
  double closest = 1e9;
  for (const WeldPath* p : layer1) {
    double along = 0.0;
    const double length = p->length_mm();
    for (std::size_t i = 0; i < p->points.size(); ++i) {
      if (i > 0) along += (p->points[i] - p->points[i - 1]).norm();
      if (along < dc || length - along < dc) continue;
      for (const WeldPath* q : layer1) {
        if (q == p || q->region != p->region) continue;
        for (const Eigen::Vector3d& x : q->points) closest = std::min(closest, (x - p->points[i]).norm());
      }
    }
  }
  EXPECT_GE(closest, 0.75 * dc);
  EXPECT_LE(r.spacing_error_pct_max, spacing_error_pct);
}

TEST(WeldLayersMatrix, OneCrater) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{0.0, 0.0, 15.0, 2.0}};
  expect_refilled(c, plan(c));
}

TEST(WeldLayersMatrix, FourCratersTwoOverlapping) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{-35.0, -15.0, 10.0, 1.5}, Crater{30.0, 12.0, 12.0, 2.0}, Crater{5.0, -12.0, 8.0, 1.0},
                     Crater{14.0, -8.0, 8.0, 1.2}};
  const WeldLayerResult r = plan(c);
  expect_refilled(c, r);
  EXPECT_EQ(r.damage.regions.size(), 3u);  // the overlapping two are one region
}

TEST(WeldLayersMatrix, CraterAtTheBorder) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{0.0, 0.0, 12.0, 1.5}, Crater{55.0, -30.0, 14.0, 2.0}};  // the second runs off two edges
  const WeldLayerResult r = plan(c);
  expect_refilled(c, r);
  ASSERT_EQ(r.damage.regions.size(), 2u);
  EXPECT_TRUE(r.damage.regions[0].at_border || r.damage.regions[1].at_border);
  EXPECT_GE(r.border_rims, 1u);
  EXPECT_TRUE(r.regions_without_rim.empty());
}

TEST(WeldLayersMatrix, RingShapedCrater) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{0.0, 0.0, 20.0, 1.5, 8.0}};
  const WeldLayerResult r = plan(c);
  expect_refilled(c, r);
  EXPECT_EQ(r.rims.size(), 2u);  // outer and inner rim
}

TEST(WeldLayersMatrix, ShallowCrater) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{0.0, 0.0, 12.0, 0.3}};
  expect_refilled(c, plan(c));
  c.blade.noise_mm = 0.1;  // 0.3 mm is within 6 sigma of this noise: not detectable, and said so
  const WeldLayerResult r = plan(c);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.termination.find("no damage found"), std::string::npos) << r.termination;
}

TEST(WeldLayersMatrix, DeepCraterOnATightlyCurvedBlade) {
  Case c = base_case(0.01);
  c.blade.length_mm = 60.0, c.blade.width_mm = 50.0, c.blade.cols = 61, c.blade.rows = 51;  // 1 mm grid
  c.blade.chord_radius_mm = 60.0, c.blade.span_radius_mm = 80.0;
  c.blade.craters = {Crater{0.0, 0.0, 14.0, 6.0}};
  c.weld.torch_distance_mm = 0.0;
  const WeldLayerResult r = plan(c);
  // The half-step paths focus in the 6 mm bowl (positive Gaussian curvature): the reported spacing error of the
  // construction paths reaches ~35 % there; the layer-1 paths themselves stay >= 0.75 dc apart (checked).
  expect_refilled(c, r, 40.0);
  EXPECT_EQ(r.layers, 6);
  for (int k = 0; k < r.layers; ++k) EXPECT_GT(r.paths_per_layer[static_cast<std::size_t>(k)], 0) << k;
}

TEST(WeldLayersMatrix, LipsAndBumps) {
  Case c = base_case(0.0);  // the case: noise-free, 3 mm deep, a 0.4 mm lip beyond the rim; and a bump
  c.blade.craters = {Crater{0.0, 0.0, 20.0, 3.0, 0.0, 0.4, 6.0}};
  c.blade.bumps = {Bump{-42.0, 25.0, 7.0, 3.0}};
  const WeldLayerResult r = plan(c);
  EXPECT_LT(r.noise_mm, 0.002);
  EXPECT_DOUBLE_EQ(r.depth_threshold_mm, 0.01);
  expect_refilled(c, r);
  EXPECT_EQ(r.damage.regions.size(), 1u);
}

// Raised lips that reach the grid's border (the patch measured with a small margin): the undamaged surface is a
// minority of the nodes, the lips are geometry, not a registration bias. One crater, two craters, a 0.2 mm grid; a
// real 0.3 mm offset under the same lips is still refused in check mode.
TEST(WeldLayersMatrix, LipsReachingTheBorderAreNotABias) {
  struct Lipped {
    double size_mm, spacing_mm;
    std::vector<Crater> craters;
  };
  const Lipped cases[] = {
      {40.0, 1.0, {Crater{0.0, 0.0, 10.0, 3.0, 0.0, 0.4, 10.0}}},
      {40.0, 1.0, {Crater{-9.0, -6.0, 8.0, 2.5, 0.0, 0.4, 8.0}, Crater{9.0, 7.0, 7.0, 2.0, 0.0, 0.3, 8.0}}},
      {24.0, 0.2, {Crater{0.0, 0.0, 6.0, 2.5, 0.0, 0.4, 6.0}}},
  };
  for (const Lipped& l : cases) {
    SCOPED_TRACE(l.spacing_mm);
    SCOPED_TRACE(l.craters.size());
    Case c = base_case(0.01);
    c.blade.length_mm = c.blade.width_mm = l.size_mm;
    c.blade.rows = c.blade.cols = static_cast<int>(std::lround(l.size_mm / l.spacing_mm)) + 1;
    c.blade.chord_radius_mm = c.blade.span_radius_mm = 1e6, c.blade.twist_per_mm = 0.0;
    c.blade.craters = l.craters;
    c.weld.outward_side = 1;  // lip and crater volumes are alike here: the side is given, as the job asks
    const WeldLayerResult r = plan(c);
    EXPECT_FALSE(r.damage.bias_significant) << r.damage.bias_offset_mm << " mm";
    EXPECT_LT(std::abs(r.damage.bias_offset_mm), 0.01);
    expect_refilled(c, r);
    c.blade.reference_offset_mm = 0.3;
    const WeldLayerResult shifted = plan(c);
    EXPECT_FALSE(shifted.ok);
    EXPECT_NE(shifted.termination.find("offset"), std::string::npos) << shifted.termination;
    EXPECT_NEAR(shifted.damage.bias_offset_mm, -0.3, 0.01);
  }
}

TEST(WeldLayersMatrix, NoiseLevels) {
  for (const double noise : {0.0, 0.05, 0.1}) {
    SCOPED_TRACE(noise);
    Case c = base_case(noise);
    c.blade.craters = {Crater{-10.0, 5.0, 16.0, 2.5}};
    expect_refilled(c, plan(c));
  }
}

TEST(WeldLayersMatrix, TorchDistance) {
  for (const double w : {5.0, 10.0}) {  // Eq. (5) widens the spacing in the bowl: no crossings left, damage covered
    SCOPED_TRACE(w);
    Case c = base_case(0.01);
    c.blade.craters = {Crater{0.0, 0.0, 15.0, 2.0}, Crater{35.0, 10.0, 10.0, 1.5}};
    c.weld.torch_distance_mm = w;
    const WeldLayerResult r = plan(c);
    expect_refilled(c, r, 40.0);
    EXPECT_EQ(r.path_crossings, 0u);
  }
}

// The bars measured on the plan against the generator's truth: the share of the true damage (and of each
// generated crater) within half a bead (dc / 2) of layer 1, and the most path length of any layer within half a bead
// of another path of the layer that is not a piece of the same line (beads over beads).
struct Bars {
  double coverage_pct = 0.0, crater_pct_min = 100.0, overlap_mm = 0.0;
};

Bars measure_bars(const Case& c, const WeldLayerResult& r) {
  const ErodedOptions& o = c.blade;
  const double half = 0.5 * c.weld.bead_spacing_mm;
  Bars bars;
  for (int k = 1; k <= r.layers; ++k) {
    double overlap = 0.0;
    for (const WeldPath& p : r.paths) {
      if (p.layer != k) continue;
      for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
        const int pieces = std::max(1, static_cast<int>(std::ceil((p.points[i + 1] - p.points[i]).norm() / 0.2)));
        for (int j = 0; j < pieces; ++j) {
          const Eigen::Vector3d x = p.points[i] + (p.points[i + 1] - p.points[i]) * ((j + 0.5) / pieces);
          bool near = false;
          for (const WeldPath& q : r.paths) {
            if (q.layer != k || &q == &p || q.line == p.line || near) continue;
            for (std::size_t m = 0; m + 1 < q.points.size() && !near; ++m) {
              const Eigen::Vector3d a = q.points[m], ab = q.points[m + 1] - a;
              const double t = std::clamp((x - a).dot(ab) / std::max(ab.squaredNorm(), 1e-30), 0.0, 1.0);
              near = (a + t * ab - x).norm() < half;
            }
          }
          if (near) overlap += (p.points[i + 1] - p.points[i]).norm() / pieces;
        }
      }
    }
    bars.overlap_mm = std::max(bars.overlap_mm, overlap);
  }
  std::vector<Eigen::Vector3d> dense;
  for (const WeldPath& p : r.paths) {
    if (p.layer != 1) continue;
    for (std::size_t i = 0; i + 1 < p.points.size(); ++i) {
      for (int k = 0; k < 16; ++k) dense.push_back(p.points[i] + (p.points[i + 1] - p.points[i]) * (k / 16.0));
    }
    dense.push_back(p.points.back());
  }
  std::size_t damaged = 0, covered = 0;
  std::vector<std::size_t> own(o.craters.size(), 0), own_covered(o.craters.size(), 0);
  std::vector<ErodedOptions> singles(o.craters.size(), o);
  for (std::size_t i = 0; i < singles.size(); ++i) singles[i].craters.assign(1, o.craters[i]);
  for (int row = 0; row < o.rows; ++row) {
    for (int col = 0; col < o.cols; ++col) {
      const double x = -0.5 * o.length_mm + o.length_mm * col / (o.cols - 1);
      const double y = -0.5 * o.width_mm + o.width_mm * row / (o.rows - 1);
      if (!(crater_depth(o, x, y) > r.depth_threshold_mm + 4.0 * o.noise_mm)) continue;
      const Eigen::Vector3d node = true_eroded(o, x, y);
      double nearest = 1e9;
      for (const Eigen::Vector3d& q : dense) nearest = std::min(nearest, (q - node).norm());
      const bool in = nearest <= half + 4.0 * o.noise_mm;
      ++damaged, covered += in;
      for (std::size_t i = 0; i < o.craters.size(); ++i) {
        if (crater_depth(singles[i], x, y) > r.depth_threshold_mm + 4.0 * o.noise_mm) ++own[i], own_covered[i] += in;
      }
    }
  }
  bars.coverage_pct = damaged > 0 ? 100.0 * double(covered) / double(damaged) : 0.0;
  for (std::size_t i = 0; i < own.size(); ++i) {
    if (own[i] > 0)
      bars.crater_pct_min = std::min(bars.crater_pct_min, 100.0 * double(own_covered[i]) / double(own[i]));
  }
  return bars;
}

// Torch standoffs 0-10 mm on a blade, an elongated crater in a cylindrical reference (a floor radius of ~2.9 mm along
// its short axis) and a bean-shaped crater (two overlapping pits) on a saddle-shaped reference: each plan is right
// (>= 90 % of the damage and >= 85 % of each crater under layer 1 with the bead width = dc, <= 2 mm of any layer within
// half a bead of another of its paths) with exit 0, or it is refused and is indeed wrong by one of those bars. Before,
// the paths were offset at the torch (Eq. 5) and folded: 47.8 mm of 128.6 mm within half a bead at 3 mm, exit 0.
TEST(WeldLayersMatrix, StandoffsZeroToTenMillimetres) {
  std::vector<Case> surfaces;
  Case blade = base_case(0.01);
  blade.blade.craters = {Crater{0.0, 0.0, 15.0, 2.0}, Crater{35.0, 10.0, 10.0, 1.5}};
  surfaces.push_back(blade);
  Case cylinder = base_case(0.02);
  cylinder.blade.length_mm = 40.0, cylinder.blade.width_mm = 40.0, cylinder.blade.rows = cylinder.blade.cols = 81;
  cylinder.blade.chord_radius_mm = 40.0, cylinder.blade.span_radius_mm = 1e6, cylinder.blade.twist_per_mm = 0.0;
  cylinder.blade.craters.assign(1, Crater{});
  cylinder.blade.craters[0].radius_mm = 12.0, cylinder.blade.craters[0].radius_y_mm = 5.0;  // 24 x 10 x 2.5 mm
  cylinder.blade.craters[0].depth_mm = 2.5;
  surfaces.push_back(cylinder);
  Case saddle = base_case(0.02);
  saddle.blade.length_mm = 60.0, saddle.blade.width_mm = 50.0, saddle.blade.rows = 51, saddle.blade.cols = 61;
  saddle.blade.twist_per_mm = 0.02;  // z = ... + 0.02 x y: saddle-shaped (twist^2 > 1 / (R_chord R_span))
  saddle.blade.craters = {Crater{-4.0, -2.0, 9.0, 2.0}, Crater{5.0, 4.0, 8.0, 1.8}};  // a bean
  surfaces.push_back(saddle);
  int right = 0;
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    for (const double w : {0.0, 3.0, 5.0, 8.0, 10.0}) {
      SCOPED_TRACE("surface " + std::to_string(i) + ", torch distance " + std::to_string(w));
      Case c = surfaces[i];
      c.weld.torch_distance_mm = w;
      const WeldLayerResult r = plan(c);
      const Bars bars = measure_bars(c, r);
      const bool meets = bars.coverage_pct >= 90.0 && bars.crater_pct_min >= 85.0 && bars.overlap_mm <= 2.0;
      EXPECT_EQ(r.ok, meets) << r.termination << "; coverage " << bars.coverage_pct << " %, crater min "
                             << bars.crater_pct_min << " %, overlap " << bars.overlap_mm << " mm";
      EXPECT_LE(r.overlap_mm_max, 2.0 + (r.ok ? 0.0 : 1e9));
      EXPECT_NEAR(r.overlap_mm_max, bars.overlap_mm, 0.5);
      right += r.ok && meets;
    }
  }
  EXPECT_GE(right, 12);  // the plans must be made, not only refused
}

// Coverage is counted with the stated bead width (default the spacing) and per crater: the three-crater blade of the
// docs, whose smallest crater (0.95 mm deep) has rim slivers between path ends. The reported figures must not exceed
// the truth's (before, beads 2g wide counted 91 % where 63-68 % were covered), and a crater below the minimum is
// exit 1.
TEST(WeldLayersMatrix, CoverageWithTheStatedBeadWidthPerCrater) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{0.0, 0.0, 15.0, 2.0}, Crater{35.0, 10.0, 8.0, 1.0}, Crater{55.0, -30.0, 10.0, 1.5}};
  c.weld.torch_distance_mm = 2.0;
  WeldLayerResult r = plan(c);
  ASSERT_TRUE(r.ok) << r.termination;
  EXPECT_DOUBLE_EQ(r.bead_width_mm, 3.0);
  ASSERT_EQ(r.crater_coverage_pct.size(), 3u);
  const Bars bars = measure_bars(c, r);
  const double smallest = *std::min_element(r.crater_coverage_pct.begin(), r.crater_coverage_pct.end());
  // Never more than the truth's figures (those count nodes 4 sigma past the threshold, the job's every damaged node).
  EXPECT_LE(smallest, bars.crater_pct_min + 1.0);
  EXPECT_LE(r.damage_coverage_pct, bars.coverage_pct + 1.0);
  EXPECT_LT(smallest, 90.0);  // slivers at the rim: the bead is no wider than its spacing
  EXPECT_GE(smallest, 85.0);
  c.weld.min_crater_coverage_pct = 90.0;
  r = plan(c);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.termination.find("layer 1 covers"), std::string::npos) << r.termination;
  c.weld.bead_width_mm = 3.6;  // beads wider than their spacing, as laid: every crater covered
  r = plan(c);
  EXPECT_TRUE(r.ok) << r.termination;
  for (const double pct : r.crater_coverage_pct) EXPECT_GE(pct, 99.0);
}

// A dense grid (0.4 x 0.27 mm) with noise 0.02 mm: each crater's fringe, where its depth falls through the threshold, is
// broken up by the noise. It stays one crater: islands planned as craters of their own laid their beads over the
// crater's (refused, 2.8 mm of overlap on a 301 x 301 grid). Three seeds.
TEST(WeldLayersMatrix, NoisyFringeOnADenseGridStaysOneCrater) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    Case c = base_case(0.02);
    c.blade.seed = seed;
    c.blade.cols = 301, c.blade.rows = 301;
    c.blade.craters = {Crater{0.0, 0.0, 15.0, 2.0}, Crater{35.0, 10.0, 8.0, 1.0}, Crater{55.0, -30.0, 10.0, 1.5}};
    c.weld.torch_distance_mm = 2.0;
    const WeldLayerResult r = plan(c);
    EXPECT_EQ(r.damage.regions.size(), 3u);
    EXPECT_LE(r.overlap_mm_max, c.weld.max_overlap_mm);
    expect_refilled(c, r);
  }
}

TEST(WeldLayersMatrix, GridSpacings) {
  for (const double spacing : {0.2, 1.0, 4.0}) {
    SCOPED_TRACE(spacing);
    Case c = base_case(0.01);
    c.blade.length_mm = spacing < 0.5 ? 40.0 : 120.0, c.blade.width_mm = spacing < 0.5 ? 30.0 : 80.0;
    c.blade.cols = static_cast<int>(std::lround(c.blade.length_mm / spacing)) + 1;
    c.blade.rows = static_cast<int>(std::lround(c.blade.width_mm / spacing)) + 1;
    c.blade.craters = {Crater{0.0, 0.0, spacing < 0.5 ? 10.0 : 20.0, 2.0}};
    expect_refilled(c, plan(c));
  }
}

TEST(WeldLayersMatrix, ReferenceOffsetOrTilted) {
  Case c = base_case(0.01);
  c.blade.craters = {Crater{0.0, 0.0, 15.0, 2.0}};
  c.blade.reference_offset_mm = 0.3;
  WeldLayerResult r = plan(c);
  EXPECT_FALSE(r.ok);  // check mode: a registration error is not refilled silently
  EXPECT_NE(r.termination.find("offset"), std::string::npos) << r.termination;
  EXPECT_NEAR(r.damage.bias_offset_mm, -0.3, 0.02);  // along the normal: n_z 0.93..1 over the blade
  c.weld.bias = BiasMode::kRemove;
  expect_refilled(c, plan(c));
  c.blade.reference_offset_mm = 1.0;  // a 1 mm shift: reported
  c.weld.bias = BiasMode::kCheck;
  r = plan(c);
  EXPECT_FALSE(r.ok);
  EXPECT_NEAR(r.damage.bias_offset_mm, -1.0, 0.05);
  c.blade.reference_offset_mm = 0.0;
  c.blade.reference_tilt_deg = 0.5;
  c.weld.bias = BiasMode::kRemove;
  r = plan(c);
  expect_refilled(c, r);
  EXPECT_NEAR(r.damage.bias_tilt_deg, 0.5, 0.05);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.front().find("removed"), std::string::npos);
}

}  // namespace
}  // namespace conform
