// Parallel paths (Simas, Dias & Guenther) on analytic surfaces: straight lines exactly dc apart on a plane, surface
// distance within 2% of g (Eq. 5) on a cylinder and a sphere, every step's chord error <= delta, loops removed.

#include "conform/toolpath/weld/parallel_paths.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "analytic_surfaces.h"
#include "conform/core/error.h"

namespace conform {
namespace {

// The sagitta of a chord c on a circle of radius rho: the exact chord error of a step along that circle.
double sagitta(double chord, double rho) { return rho - std::sqrt(rho * rho - 0.25 * chord * chord); }

TEST(LateralSpacing, Eq5FlatConvexConcave) {
  EXPECT_DOUBLE_EQ(lateral_spacing(2.0, 10.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(lateral_spacing(2.0, 10.0, -1.0 / 50.0), 50.0 / 60.0 * 2.0);  // convex: R* / (R* + w) dc
  EXPECT_DOUBLE_EQ(lateral_spacing(2.0, 10.0, 1.0 / 50.0), 60.0 / 50.0 * 2.0);   // concave: (R* + w) / R* dc
  EXPECT_DOUBLE_EQ(lateral_spacing(2.0, 0.0, -1.0 / 50.0), 2.0);
}

TEST(ChordForError, Eq1) {
  EXPECT_DOUBLE_EQ(chord_for_error(0.05, 100.0), 2.0 * std::sqrt(0.05 * 99.95));
  // The paper's chord 2 sqrt(delta (rho - delta)) has a sagitta of about delta / 2: the bound holds with margin.
  EXPECT_LE(sagitta(chord_for_error(0.05, 100.0), 100.0), 0.05);
  EXPECT_GT(sagitta(chord_for_error(0.05, 100.0), 100.0), 0.45 * 0.05);
  EXPECT_TRUE(std::isinf(chord_for_error(0.05, INFINITY)));
}

TEST(ParallelPaths, PlaneGivesStraightLinesExactlyDcApart) {
  const test::Plane plane;
  ParallelPathOptions o;
  o.spacing_mm = 2.0;
  o.torch_distance_mm = 5.0;  // flat: no effect
  o.chord_error_mm = 0.05;
  o.max_step_mm = 5.0;
  o.max_paths = 10;
  const ParallelPathResult r = parallel_paths(plane, {{10.0, 10.0}, {90.0, 10.0}}, o);
  ASSERT_TRUE(r.ok);
  ASSERT_EQ(r.paths.size(), 10u);
  for (std::size_t k = 0; k < r.paths.size(); ++k) {
    for (const Eigen::Vector3d& p : r.paths[k].points) {
      EXPECT_NEAR(p.y(), 10.0 + 2.0 * static_cast<double>(k), 1e-9);  // a straight line at exactly k dc (rounding only)
      EXPECT_EQ(p.z(), 0.0);
    }
    EXPECT_NEAR(r.paths[k].points.front().x(), 10.0, 1e-9);
    EXPECT_NEAR(r.paths[k].points.back().x(), 90.0, 1e-9);
    for (std::size_t i = 1; i < r.paths[k].points.size(); ++i) {
      EXPECT_LE((r.paths[k].points[i] - r.paths[k].points[i - 1]).norm(), 5.0 + 1e-9);
    }
  }
  EXPECT_EQ(r.chord_error_mm_max, 0.0);
  EXPECT_EQ(r.loops_removed, 0u);
  EXPECT_LT(spacing_error_pct_max(plane, r.paths[0], r.paths[1]), 1e-9);
}

TEST(ParallelPaths, CylinderAcrossTheAxisIsConvex) {
  const test::Cylinder cylinder(50.0);
  ParallelPathOptions o;
  o.spacing_mm = 2.0;
  o.torch_distance_mm = 10.0;
  o.chord_error_mm = 0.02;
  o.max_paths = 12;
  const ParallelPathResult r = parallel_paths(cylinder, {{0.0, -20.0}, {0.0, 20.0}}, o);
  ASSERT_EQ(r.paths.size(), 12u);
  const double g = 50.0 / 60.0 * 2.0;  // Eq. (5), convex
  for (std::size_t k = 0; k + 1 < r.paths.size(); ++k) {
    for (std::size_t i = 0; i < r.paths[k].uv.size(); ++i) {
      EXPECT_NEAR(r.paths[k].spacing_mm[i], g, 1e-12);
      // Neighbour paths are generators u = const: the surface distance is R |du|. 2% is the bound.
      const double distance = 50.0 * std::abs(r.paths[k + 1].uv[0].x() - r.paths[k].uv[i].x());
      EXPECT_LT(std::abs(distance - g) / g, 0.02);
      EXPECT_NEAR(distance, g, 1e-9);  // Newton solves the exact constraint: far better than 2%
    }
  }
  EXPECT_GT(r.newton_offsets, 0u);
}

TEST(ParallelPaths, CylinderAlongTheAxisIsFlatAcrossAndChordErrorHolds) {
  const test::Cylinder cylinder(30.0);
  ParallelPathOptions o;
  o.spacing_mm = 2.0;
  o.torch_distance_mm = 10.0;
  o.chord_error_mm = 0.05;
  o.max_paths = 6;
  const ParallelPathResult r = parallel_paths(cylinder, {{-1.0, 0.0}, {1.0, 0.0}}, o);
  ASSERT_EQ(r.paths.size(), 6u);
  for (std::size_t k = 0; k < r.paths.size(); ++k) {
    for (std::size_t i = 0; i < r.paths[k].points.size(); ++i) {
      EXPECT_NEAR(r.paths[k].points[i].z(), 2.0 * static_cast<double>(k), 1e-9);  // g = dc: across is straight
      if (i > 0) {
        const double chord = (r.paths[k].points[i] - r.paths[k].points[i - 1]).norm();
        EXPECT_LE(sagitta(chord, 30.0), 0.05 + 1e-12);  // each step of the circle: chord error <= delta
      }
    }
  }
  EXPECT_LE(r.chord_error_mm_max, 0.05);
  EXPECT_GT(r.chord_error_mm_max, 0.02);  // the steps use Eq. (1)'s allowance (about delta / 2), not a tiny step
}

TEST(ParallelPaths, SphereLatitudesWithinTwoPercentOfG) {
  const test::Sphere sphere(40.0);
  ParallelPathOptions o;
  o.spacing_mm = 3.0;
  o.torch_distance_mm = 8.0;
  o.chord_error_mm = 0.03;
  o.max_paths = 10;
  const ParallelPathResult r = parallel_paths(sphere, {{-1.0, 0.0}, {1.0, 0.0}}, o);
  ASSERT_EQ(r.paths.size(), 10u);
  const double g = 40.0 / 48.0 * 3.0;  // convex
  for (std::size_t k = 0; k + 1 < r.paths.size(); ++k) {
    const double latitude = r.paths[k].uv[0].y();
    for (std::size_t i = 0; i < r.paths[k].uv.size(); ++i) {
      EXPECT_NEAR(r.paths[k].uv[i].y(), latitude, 1e-9);  // a path stays on its latitude circle
      const double distance = 40.0 * (r.paths[k + 1].uv[0].y() - r.paths[k].uv[i].y());  // along the meridian
      EXPECT_LT(std::abs(distance - g) / g, 0.02);
      if (i > 0) {
        const double chord = (r.paths[k].points[i] - r.paths[k].points[i - 1]).norm();
        EXPECT_LE(sagitta(chord, 40.0 * std::cos(latitude)), 0.03 + 1e-9);  // the latitude circle's radius
      }
    }
    EXPECT_LT(spacing_error_pct_max(sphere, r.paths[k], r.paths[k + 1]), 2.0);
  }
}

TEST(OffsetPoint, LeftOfTheDirectionOnAPlaneAndOnTheCylinderExactly) {
  const test::Plane plane;
  ParallelPathOptions o;
  o.spacing_mm = 2.0;
  Eigen::Vector2d x;
  double g = 0.0;
  bool exact = true;
  ASSERT_TRUE(offset_point(plane, {10.0, 10.0}, {1.0, 1.0}, o, &x, &g, &exact));
  EXPECT_NEAR((x - Eigen::Vector2d(10.0 - std::sqrt(2.0), 10.0 + std::sqrt(2.0))).norm(), 0.0, 1e-12);
  EXPECT_EQ(g, 2.0);
  EXPECT_FALSE(exact);  // flat: Eq. (8-9) is exact already
  EXPECT_FALSE(offset_point(plane, {99.5, 10.0}, {0.0, -1.0}, o, &x, &g, &exact));  // off the domain
  const test::Cylinder cylinder(10.0);
  o.torch_distance_mm = 0.0;
  o.spacing_mm = 5.0;  // g / R = 0.5: far from small, Newton needed
  ASSERT_TRUE(offset_point(cylinder, {0.0, 0.0}, {0.0, 1.0}, o, &x, &g, &exact));
  EXPECT_TRUE(exact);
  EXPECT_NEAR(10.0 * std::abs(x.x()), 5.0, 1e-9);  // the arc g on the circle, not the first-order g / R
  EXPECT_NEAR(x.y(), 0.0, 1e-12);
  double given = 3.0;
  ASSERT_TRUE(offset_point_by(cylinder, {0.0, 0.0}, {0.0, 1.0}, o, &x, &given, &exact));
  EXPECT_NEAR(10.0 * std::abs(x.x()), 3.0, 1e-9);
}

TEST(RemoveLoops, CutsTheLoopAtTheCrossing) {
  // 0 -> 4 along x, back under itself in a loop, and on: the segment (3,-1)-(3,1)... crosses (2,0)-(4,0) at (3,0).
  const std::vector<Eigen::Vector2d> looped = {{0, 0}, {2, 0}, {4, 0}, {4, -1}, {3, -1}, {3, 1}, {3, 2}};
  std::size_t loops = 0, points = 0;
  const std::vector<Eigen::Vector2d> out = remove_loops(looped, &loops, &points);
  EXPECT_TRUE(self_intersects(looped));
  EXPECT_FALSE(self_intersects(out));
  EXPECT_EQ(loops, 1u);
  EXPECT_EQ(points, 3u);  // (4,0), (4,-1), (3,-1)
  ASSERT_EQ(out.size(), 5u);
  EXPECT_NEAR((out[2] - Eigen::Vector2d(3, 0)).norm(), 0.0, 1e-12);
}

TEST(ParallelPaths, ConcaveOffsetsLoseTheirLoops) {
  // A V opening upwards, offset into the V: near the corner the offsets of the two legs cross each other (a
  // swallowtail), which the heuristic must cut out.
  const test::Plane plane;
  ParallelPathOptions o;
  o.spacing_mm = 2.0;
  o.chord_error_mm = 0.01;
  o.max_step_mm = 0.5;
  o.max_paths = 6;
  const ParallelPathResult r = parallel_paths(plane, {{40.0, 60.0}, {50.0, 50.0}, {60.0, 60.0}}, o);
  ASSERT_EQ(r.paths.size(), 6u);
  EXPECT_GT(r.loops_removed, 0u);
  for (const SurfacePath& path : r.paths) EXPECT_FALSE(self_intersects(path.uv));
  // The corner rises by dc / cos(45 deg) per path once the legs' offsets meet: path 5's lowest point.
  double lowest = 1e9;
  for (const Eigen::Vector3d& p : r.paths[5].points) lowest = std::min(lowest, p.y());
  EXPECT_GT(lowest, 50.0 + 4.0 * 2.0);
}

TEST(ParallelPaths, PathsLeavingTheDomainEndOnItsBorder) {
  const test::Plane plane;  // [0, 100]^2
  ParallelPathOptions o;
  o.spacing_mm = 2.0;
  o.chord_error_mm = 0.05;
  o.max_paths = 5;
  // A slanted reference from the left border: its parallels (to the left, +v) start beyond u = 0, and are clipped there
  // instead of losing their first step.
  const ParallelPathResult r = parallel_paths(plane, {{0.0, 10.0}, {100.0, 30.0}}, o);
  ASSERT_EQ(r.paths.size(), 5u);
  for (std::size_t k = 1; k < r.paths.size(); ++k) {
    EXPECT_NEAR(r.paths[k].uv.front().x(), 0.0, 1e-9) << k;
    // Still on the straight line 2 k mm from the reference: the offset line v = 10 + u / 5 + 2 k sqrt(1.04).
    EXPECT_NEAR(r.paths[k].uv.front().y(), 10.0 + 2.0 * static_cast<double>(k) * std::sqrt(1.04), 1e-6) << k;
  }
}

TEST(RemoveCusps, CutsReversalsAndRepeats) {
  std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {1.5, 0, 0}, {3, 0, 0}, {3, 0, 0}, {4, 0, 0}};
  std::vector<Eigen::Vector2d> uv;
  for (const Eigen::Vector3d& x : p) uv.emplace_back(x.x(), 7.0);
  EXPECT_EQ(remove_cusps(&p, &uv), 2u);  // the turn back at 2 and the repeated 3
  ASSERT_EQ(p.size(), 5u);
  ASSERT_EQ(uv.size(), 5u);
  const double expected[] = {0.0, 1.0, 1.5, 3.0, 4.0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_EQ(p[i].x(), expected[i]);
    EXPECT_EQ(uv[i].x(), expected[i]);
  }
  EXPECT_EQ(remove_cusps(&p, &uv), 0u);
}

TEST(ParallelPaths, RejectsBadOptions) {
  const test::Plane plane;
  ParallelPathOptions o;
  o.spacing_mm = 0.0;
  EXPECT_THROW(parallel_paths(plane, {{0, 0}, {1, 0}}, o), Error);
  EXPECT_THROW(parallel_paths(plane, {{0, 0}}, ParallelPathOptions{}), Error);
}

}  // namespace
}  // namespace conform
