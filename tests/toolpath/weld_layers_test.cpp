// Weld layers on a generated eroded blade (datasets/eroded.h): the rim found where the crater is as deep as the
// threshold, every point inside it, layers interleaved and stacked, figures within bounds; no damage -> not ok.

#include "conform/toolpath/weld/weld_layers.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/datasets/eroded.h"
#include "conform/toolpath/weld/parallel_paths.h"

namespace conform {
namespace {

ErodedOptions small_blade() {
  ErodedOptions o;
  o.rows = 21, o.cols = 31;
  o.length_mm = 60.0, o.width_mm = 40.0;
  o.craters = {Crater{2.0, -1.0, 10.0, 1.5}};
  o.noise_mm = 0.005;
  return o;
}

SurfaceGrid grid_of(int rows, int cols, const std::vector<Eigen::Vector3d>& points) { return {rows, cols, points}; }

WeldLayerOptions weld_options() {
  WeldLayerOptions o;
  o.bead_spacing_mm = 2.0;
  o.layer_height_mm = 0.6;
  o.chord_error_mm = 0.05;
  o.torch_distance_mm = 5.0;
  return o;
}

TEST(WeldLayers, FindsTheRimAndFillsTheCrater) {
  const ErodedOptions blade = small_blade();
  const ErodedScan scan = generate_eroded(blade);
  const BezierNetwork eroded(grid_of(scan.rows, scan.cols, scan.eroded));
  const BezierNetwork reference(grid_of(scan.rows, scan.cols, scan.reference));
  const WeldLayerOptions o = weld_options();
  const WeldLayerResult r = plan_weld_layers(eroded, reference, o);
  ASSERT_TRUE(r.ok) << r.termination;
  EXPECT_NEAR(r.noise_mm, 0.005, 0.0015);  // MAD of ~600 samples: ~10 % scatter, plus the spline's own error
  EXPECT_TRUE(r.threshold_estimated);
  EXPECT_DOUBLE_EQ(r.depth_threshold_mm, std::max(6.0 * r.noise_mm, 0.01));
  EXPECT_EQ(r.layers, 3);  // ceil(1.5 / 0.6)
  ASSERT_EQ(r.rims.size(), 1u);
  // The rim where the crater is as deep as the threshold: rho_t = a sqrt(1 - cbrt(t / D)). 0.3 mm: near the rim the
  // crater deepens by ~0.05 mm per mm, so noise (0.005) and spline error (~0.005) move the rim by ~0.2 mm.
  const double rho_t = 10.0 * std::sqrt(1.0 - std::cbrt(r.depth_threshold_mm / 1.5));
  for (const IntersectionPoint& p : r.rims[0].points) {
    EXPECT_NEAR(std::hypot(p.position.x() - 2.0, p.position.y() + 1.0), rho_t, 0.3);
  }
  EXPECT_LE(r.chord_error_mm_max, o.chord_error_mm);
  EXPECT_LT(r.spacing_error_pct_max, 3.0);
  ASSERT_EQ(r.coverage_pct.size(), 3u);
  EXPECT_GT(r.damage_coverage_pct, 90.0);
  EXPECT_DOUBLE_EQ(r.coverage_pct[0], r.damage_coverage_pct);
  EXPECT_GT(r.coverage_pct[1], 70.0);  // the upper layers' regions are small: their edge slivers weigh more
  std::vector<Eigen::Vector3d> layer1;
  int layers_seen = 0;
  for (const WeldPath& path : r.paths) {
    layers_seen = std::max(layers_seen, path.layer);
    const double level = (path.layer - 1) * o.layer_height_mm;
    std::vector<Eigen::Vector2d> xy;
    for (std::size_t i = 0; i < path.points.size(); ++i) {
      EXPECT_NEAR(path.normals[i].norm(), 1.0, 1e-9);
      EXPECT_GT(path.normals[i].z(), 0.8);  // outward, towards the torch
      // Layers are lifted along the reference's normal (a vertical fill), not along the path's normal.
      const Eigen::Vector3d on_surface = path.points[i] - level * blade_normal(blade, path.points[i].x(), path.points[i].y());
      const double rho = std::hypot(on_surface.x() - 2.0, on_surface.y() + 1.0);
      EXPECT_LT(rho, rho_t + 0.3);  // inside the boundary
      // Layer k only where the crater is deeper than (k - 1) cd (0.05 mm: noise and spline error).
      const double depth = crater_depth(blade, on_surface.x(), on_surface.y());
      if (path.layer > 1) {
        EXPECT_GT(depth, level - 0.05);
      } else {
        layer1.push_back(on_surface);
      }
      xy.emplace_back(path.points[i].x(), path.points[i].y());
    }
    EXPECT_FALSE(self_intersects(xy));
  }
  EXPECT_EQ(layers_seen, 3);
  // Layer 2's beads lie between layer 1's: about dc / 2 from the nearest layer-1 point, never on top of one.
  for (const WeldPath& path : r.paths) {
    if (path.layer != 2) continue;
    for (std::size_t i = 0; i < path.points.size(); ++i) {
      const Eigen::Vector3d on_surface =
          path.points[i] - o.layer_height_mm * blade_normal(blade, path.points[i].x(), path.points[i].y());
      double nearest = 1e9;
      for (const Eigen::Vector3d& q : layer1) nearest = std::min(nearest, (q - on_surface).norm());
      EXPECT_GT(nearest, 0.3 * o.bead_spacing_mm);
    }
  }
}

TEST(WeldLayers, NoDamageIsNotOk) {
  ErodedOptions blade = small_blade();
  blade.craters.clear();
  const ErodedScan scan = generate_eroded(blade);
  const WeldLayerResult r = plan_weld_layers(BezierNetwork(grid_of(scan.rows, scan.cols, scan.eroded)),
                                             BezierNetwork(grid_of(scan.rows, scan.cols, scan.reference)),
                                             weld_options());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.termination.find("no damage found"), std::string::npos) << r.termination;
  EXPECT_TRUE(r.paths.empty());
}

// Honest status: an ambiguous side is not ok, explicit layers beyond the depth are warned about, limits throw naming
// themselves.
TEST(WeldLayers, StatusAndLimits) {
  ErodedOptions blade = small_blade();
  blade.bumps = {Bump{-18.0, 10.0, 10.0, 1.5}};  // as large as the crater: which side is damage?
  ErodedScan scan = generate_eroded(blade);
  WeldLayerResult r = plan_weld_layers(BezierNetwork(grid_of(scan.rows, scan.cols, scan.eroded)),
                                       BezierNetwork(grid_of(scan.rows, scan.cols, scan.reference)), weld_options());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.termination.find("ambiguous"), std::string::npos) << r.termination;
  WeldLayerOptions o = weld_options();
  o.outward_side = 1;  // told: the crater is the damage
  r = plan_weld_layers(BezierNetwork(grid_of(scan.rows, scan.cols, scan.eroded)),
                       BezierNetwork(grid_of(scan.rows, scan.cols, scan.reference)), o);
  EXPECT_TRUE(r.ok) << r.termination;
  scan = generate_eroded(small_blade());
  const BezierNetwork eroded(grid_of(scan.rows, scan.cols, scan.eroded));
  const BezierNetwork reference(grid_of(scan.rows, scan.cols, scan.reference));
  o = weld_options();
  o.layers = 5;  // the 1.5 mm crater needs 3 of 0.6 mm
  r = plan_weld_layers(eroded, reference, o);
  EXPECT_TRUE(r.ok) << r.termination;
  ASSERT_EQ(r.paths_per_layer.size(), 5u);
  EXPECT_EQ(r.paths_per_layer[3], 0);
  EXPECT_EQ(r.paths_per_layer[4], 0);
  ASSERT_GE(r.warnings.size(), 2u);
  EXPECT_NE(r.warnings.back().find("layer 5 is empty"), std::string::npos) << r.warnings.back();
  o = weld_options();
  o.layer_height_mm = 0.001;
  try {
    plan_weld_layers(eroded, reference, o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("kMaxWeldLayers"), std::string::npos) << e.what();
  }
  o = weld_options();
  o.torch_distance_mm = 1000.0;
  EXPECT_THROW(plan_weld_layers(eroded, reference, o), Error);
  o = weld_options();
  o.chord_error_mm = 1.5;  // more than dc / 2
  EXPECT_THROW(plan_weld_layers(eroded, reference, o), Error);
}

TEST(WeldLayers, RejectsBadOptions) {
  const ErodedScan scan = generate_eroded(small_blade());
  const BezierNetwork net(grid_of(scan.rows, scan.cols, scan.reference));
  WeldLayerOptions o = weld_options();
  o.bead_spacing_mm = -1.0;
  EXPECT_THROW(plan_weld_layers(net, net, o), Error);
}

}  // namespace
}  // namespace conform
