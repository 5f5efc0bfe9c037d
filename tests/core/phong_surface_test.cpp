// PhongSurface against analytic surfaces: a sphere's flat facets lifted onto the sphere, a capped cylinder's rim
// (curved side up to the rim, flat cap), and a fold over the crease angle that stays flat on both sides.

#include "conform/core/phong_surface.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/triangle_index.h"
#include "test_meshes.h"

namespace conform {
namespace {

using V = Eigen::Vector3d;

// The closest points of random points near a sphere of radius 20 mm (a 12 x 24 mesh: 0.4 mm chord error) lifted
// onto the smooth surface: on the sphere within 5 % of the chord error (0.010 mm measured: Phong tessellation is exact
// to second order, and 15 deg facets are coarse), normals within 1 deg of the radial ones (0.6 measured).
TEST(PhongSurface, FacetsOfASphereLiftOntoTheSphere) {
  const Mesh sphere = test::lat_long_sphere(12, 24, [](double, double) { return 20.0; });
  const TriangleIndex index(sphere);
  const PhongSurface smooth(sphere);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  double worst_flat = 0.0, worst_smooth = 0.0, worst_angle = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const V q = 20.3 * V(g(rng), g(rng), g(rng)).normalized();
    const SurfacePoint s = index.closest(q);
    const PhongPoint p = smooth.lift(s);
    ASSERT_TRUE(p.lifted);
    worst_flat = std::max(worst_flat, 20.0 - s.point.norm());
    worst_smooth = std::max(worst_smooth, std::abs(p.point.norm() - 20.0));
    worst_angle = std::max(worst_angle, std::acos(std::min(1.0, p.normal.dot(p.point.normalized()))));
  }
  std::printf("sphere: flat facets up to %.4f mm inside, smooth surface within %.5f mm, normals within %.3f deg\n",
              worst_flat, worst_smooth, worst_angle * 180.0 / M_PI);
  EXPECT_GT(worst_flat, 0.2);
  EXPECT_LT(worst_smooth, 0.05 * worst_flat);
  EXPECT_LT(worst_angle, 1.0 * M_PI / 180.0);
}

// A closed cylinder (radius 10, 32 strips from rim to rim, fan caps): every side vertex is on a rim, where the side
// meets a cap at 90 deg. The side is lifted onto the cylinder (the rim's corners take the side's normals only), the
// caps stay flat.
TEST(PhongSurface, CylinderSideIsCurvedUpToTheRimAndTheCapStaysFlat) {
  Mesh m;
  const int n = 32;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * k / n;
    m.vertices.emplace_back(10 * std::cos(a), 10 * std::sin(a), 0.0);
    m.vertices.emplace_back(10 * std::cos(a), 10 * std::sin(a), 30.0);
  }
  m.vertices.emplace_back(0, 0, 0);
  m.vertices.emplace_back(0, 0, 30);
  const auto bottom = static_cast<std::int32_t>(2 * n), top = bottom + 1;
  for (int k = 0; k < n; ++k) {
    const std::int32_t b0 = 2 * k, t0 = 2 * k + 1, b1 = 2 * ((k + 1) % n), t1 = b1 + 1;
    m.faces.push_back({b0, b1, t1});
    m.faces.push_back({b0, t1, t0});
    m.faces.push_back({bottom, b1, b0});
    m.faces.push_back({top, t0, t1});
  }
  const TriangleIndex index(m);
  const PhongSurface smooth(m);
  for (int k = 0; k < 2 * n; ++k) EXPECT_EQ(smooth.smooth()[static_cast<std::size_t>(k)], 0) << k;
  for (double z : {0.5, 15.0, 29.5}) {
    for (int k = 0; k < 7; ++k) {
      const double a = 0.37 + 0.9 * k;
      const V q(10.2 * std::cos(a), 10.2 * std::sin(a), z);
      const PhongPoint p = smooth.lift(index.closest(q));
      EXPECT_TRUE(p.lifted);
      EXPECT_NEAR(std::hypot(p.point.x(), p.point.y()), 10.0, 0.002) << z << " " << a;  // flat: up to 0.048 mm
      EXPECT_NEAR(p.normal.z(), 0.0, 1e-9);
    }
  }
  const V q(3.0, -2.0, 30.5);
  const SurfacePoint s = index.closest(q);
  const PhongPoint p = smooth.lift(s);
  EXPECT_FALSE(p.lifted);
  EXPECT_EQ(p.point, s.point);
  EXPECT_NEAR(p.normal.z(), 1.0, 1e-12);
}

// Two planes folded at 90 deg along a ridge: a crease, so both stay flat (as the flat facets); at 10 deg the ridge is
// smooth and the fold is rounded. A normal count that does not match is an error.
TEST(PhongSurface, FoldOverTheCreaseAngleStaysFlat) {
  for (double fold_deg : {90.0, 10.0}) {
    const double h = std::tan(0.5 * fold_deg * M_PI / 180.0);
    Mesh roof;
    roof.vertices = {{0, 0, 0}, {1, 0, 0}, {0, -1, -h}, {1, -1, -h}, {0, 1, -h}, {1, 1, -h}};
    roof.faces = {{2, 3, 1}, {2, 1, 0}, {0, 1, 5}, {0, 5, 4}};
    const TriangleIndex index(roof);
    const PhongSurface smooth(roof);
    const SurfacePoint s = index.closest(V(0.5, 0.1, 1.0));
    const PhongPoint p = smooth.lift(s);
    if (fold_deg > 60.0) {
      EXPECT_FALSE(p.lifted);
      EXPECT_EQ(p.point, s.point);
    } else {
      EXPECT_TRUE(p.lifted);
      EXPECT_GT(p.point.z(), s.point.z());  // rounded over the ridge
    }
  }
  Mesh tri;
  tri.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.faces = {{0, 1, 2}};
  EXPECT_THROW(PhongSurface(tri, {V(0, 0, 1)}), Error);
  tri.faces = {{0, 1, 3}};
  EXPECT_THROW(PhongSurface{tri}, Error);
  // Built for lifting only (ICP), it lifts as the full one does and refuses nearest(), which needs the rims.
  tri.faces = {{0, 1, 2}};
  const PhongSurface full(tri), lift_only(tri, {}, kDefaultCreaseAngleRad, false);
  const TriangleIndex index(tri);
  const SurfacePoint s = index.closest(V(0.2, 0.2, 0.5));
  EXPECT_EQ(lift_only.lift(s).point, full.lift(s).point);
  EXPECT_NO_THROW(full.nearest(V(0.2, 0.2, 0.5), s));
  EXPECT_THROW(lift_only.nearest(V(0.2, 0.2, 0.5), s), Error);
}

// A block 40 x 30 x 20 mm with R10 fillets on its vertical edges, tessellated as CAD exports it (flat sides two
// triangles each, tangent to the fillets), coarse (4 chords a fillet, 0.19 mm chord error) and at the CAD reader's
// 0.005 mm (32 chords): exact points on the flat sides read 0 (they bulged 0.27 mm when the flat sides took the
// vertex normals averaged with the fillets' first chords), and points on the fillets read within 0.005 mm of the
// radius at 32 chords (0.0004 mm measured) and within 5 % of the chord error at 4 (0.002 mm measured).
TEST(PhongSurface, FlatSidesNextToTangentFilletsStayFlat) {
  for (int chords : {4, 32}) {
    const Mesh block = test::filleted_block(40, 30, 20, 10, chords);
    const TriangleIndex index(block);
    const PhongSurface smooth(block, vertex_normals_from_faces(block));  // as align's reference passes them
    double worst_flat = 0.0, worst_fillet = 0.0;
    for (int i = 0; i < 400; ++i) {
      const double t = (i + 0.5) / 400.0, z = 1.0 + 18.0 * std::fmod(7.31 * i, 1.0);
      // Around the outline by arc length: side (20 mm), fillet (pi/2 * 10), side (10 mm), fillet, ...
      const double side_x = 20.0, side_y = 10.0, arc = kPi / 2 * 10.0;
      double u = t * 2 * (side_x + side_y + 2 * arc);
      V p;
      bool on_fillet = false;
      const double cx[4] = {10, -10, -10, 10}, cy[4] = {5, 5, -5, -5};
      for (int c = 0; c < 4; ++c) {
        const double side = c % 2 == 0 ? side_y : side_x;
        const double a0 = kPi / 2 * c;
        if (u < side) {  // the flat side that leads into corner c
          const V start = V(cx[(c + 3) % 4], cy[(c + 3) % 4], 0) + 10.0 * V(std::cos(a0), std::sin(a0), 0);
          p = start + u * V(-std::sin(a0), std::cos(a0), 0);
          break;
        }
        u -= side;
        if (u < arc) {
          const double a = a0 + u / 10.0;
          p = V(cx[c] + 10 * std::cos(a), cy[c] + 10 * std::sin(a), 0);
          on_fillet = true;
          break;
        }
        u -= arc;
      }
      p.z() = z;
      const PhongPoint lifted = smooth.lift(index.closest(p));
      const double error = (lifted.point - p).norm();
      (on_fillet ? worst_fillet : worst_flat) = std::max(on_fillet ? worst_fillet : worst_flat, error);
    }
    std::printf("filleted block, %d chords: flat sides within %.6f mm, fillets within %.6f mm\n", chords, worst_flat,
                worst_fillet);
    EXPECT_LT(worst_flat, 1e-9) << chords;
    const double chord_error = 10.0 * (1.0 - std::cos(kPi / 4 / chords));
    EXPECT_LT(worst_fillet, std::min(0.005, 0.05 * chord_error) + (chords == 4 ? 0.005 : 0.0)) << chords;
  }
}

}  // namespace
}  // namespace conform
