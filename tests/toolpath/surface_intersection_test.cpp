// Intersection by recursive subdivision against analytic curves: a plane cutting a paraboloid, a sphere cap cut by
// a plane; both give a closed circle within the subdivision tolerance.

#include "conform/toolpath/intersection/surface_intersection.h"

#include <cmath>

#include <gtest/gtest.h>

namespace conform {
namespace {

// A network of exact patches of f over [-L, L]^2 in n x n patches (f of degree <= 3 in x and y: reproduced exactly).
BezierNetwork exact_network(const std::function<Eigen::Vector3d(double, double)>& f, double L, int n) {
  std::vector<BezierPatch> patches;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      patches.push_back(interpolating_patch([&](double u, double v) {
        return f(-L + 2 * L * (c + u) / n, -L + 2 * L * (r + v) / n);
      }));
    }
  }
  return BezierNetwork(n, n, patches);
}

TEST(SurfaceIntersection, PlaneCuttingAParaboloidGivesItsCircle) {
  const double R = 20.0, h = 5.0;  // z = (x^2 + y^2) / (2R) meets z = h on the circle of radius sqrt(2 R h)
  const BezierNetwork paraboloid = exact_network([&](double x, double y) { return Eigen::Vector3d(x, y, (x * x + y * y) / (2 * R)); }, 20.0, 4);
  const BezierNetwork plane = exact_network([&](double x, double y) { return Eigen::Vector3d(x, y, h); }, 20.0, 3);
  IntersectionOptions o;
  o.tolerance_mm = 0.3;
  const IntersectionResult r = intersect_surfaces(paraboloid, plane, o);
  ASSERT_TRUE(r.ok) << r.termination;
  ASSERT_EQ(r.curves.size(), 1u);
  const IntersectionCurve& circle = r.curves[0];
  EXPECT_TRUE(circle.closed);
  const double radius = std::sqrt(2 * R * h);
  for (const IntersectionPoint& p : circle.points) {
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), radius, o.tolerance_mm);  // the bound
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), radius, 1e-7);  // Newton: on the exact curve
    EXPECT_NEAR(p.position.z(), h, 1e-7);
  }
  EXPECT_NEAR(circle.length_mm(), 2 * M_PI * radius, 0.01 * 2 * M_PI * radius);  // polygon of points ~tol apart
  EXPECT_LT(r.max_gap_mm, 1e-8);
}

TEST(SurfaceIntersection, SphereCapAgainstAPlane) {
  const double R = 30.0, z0 = 24.0;  // the circle of radius sqrt(R^2 - z0^2) = 18
  SurfaceGrid grid;
  grid.rows = grid.cols = 21;
  for (int r = 0; r < 21; ++r) {
    for (int c = 0; c < 21; ++c) {
      const double x = -24.0 + 2.4 * c, y = -24.0 + 2.4 * r;
      grid.points.emplace_back(x, y, std::sqrt(std::max(R * R - x * x - y * y, 0.0)));
    }
  }
  const BezierNetwork sphere(grid);
  const BezierNetwork plane = exact_network([&](double x, double y) { return Eigen::Vector3d(x, y, z0); }, 25.0, 2);
  IntersectionOptions o;
  o.tolerance_mm = 0.3;
  const IntersectionResult r = intersect_surfaces(sphere, plane, o);
  ASSERT_TRUE(r.ok) << r.termination;
  ASSERT_GE(r.curves.size(), 1u);
  EXPECT_TRUE(r.curves[0].closed);
  for (const IntersectionPoint& p : r.curves[0].points) {
    // Within the subdivision tolerance of the analytic circle (the spline's own error on a 2.4 mm grid is ~1e-2).
    EXPECT_NEAR(p.position.norm(), R, o.tolerance_mm);
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), 18.0, o.tolerance_mm);
    EXPECT_NEAR(std::hypot(p.position.x(), p.position.y()), 18.0, 0.02);  // Newton: only the spline's error left
  }
}

TEST(SurfaceIntersection, WorkIsBounded) {
  const BezierNetwork paraboloid = exact_network([](double x, double y) { return Eigen::Vector3d(x, y, (x * x + y * y) / 40.0); }, 20.0, 4);
  const BezierNetwork plane = exact_network([](double x, double y) { return Eigen::Vector3d(x, y, 5.0); }, 20.0, 3);
  IntersectionOptions o;
  o.tolerance_mm = 0.3;
  const IntersectionResult full = intersect_surfaces(paraboloid, plane, o);
  ASSERT_TRUE(full.ok);
  EXPECT_GT(full.box_pairs, 100u);
  o.max_box_pairs = 100;  // issue 18: the work any input can cause has a limit, and hitting it is said
  const IntersectionResult r = intersect_surfaces(paraboloid, plane, o);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(r.work_limit_hit);
  EXPECT_TRUE(r.curves.empty());
  EXPECT_NE(r.termination.find("max_box_pairs"), std::string::npos) << r.termination;
}

TEST(SurfaceIntersection, ApartSurfacesDoNotIntersect) {
  const BezierNetwork a = exact_network([](double x, double y) { return Eigen::Vector3d(x, y, 0.0); }, 10.0, 2);
  const BezierNetwork b = exact_network([](double x, double y) { return Eigen::Vector3d(x, y, 0.5); }, 10.0, 2);
  const IntersectionResult r = intersect_surfaces(a, b);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(r.curves.empty());
  EXPECT_EQ(r.termination, "the surfaces do not intersect");
  const std::vector<Eigen::Vector2d> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(polygon_contains(square, {0.5, 0.5}));
  EXPECT_FALSE(polygon_contains(square, {1.5, 0.5}));
}

}  // namespace
}  // namespace conform
