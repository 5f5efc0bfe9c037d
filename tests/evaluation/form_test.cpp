// evaluation/form.h: the least-squares plane and sphere against generated points with known parameters, and the form
// zone's trimmed and untrimmed widths against sorted values.

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "conform/evaluation/form.h"

namespace conform {
namespace {

TEST(Form, PlaneThroughNoisyPointsHasTheirNormal) {
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  const Eigen::Vector3d n = Eigen::Vector3d(0.1, -0.2, 1.0).normalized();
  const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 5000; ++i) {
    points.push_back(Eigen::Vector3d(3, 4, 5) + u(random) * e1 + u(random) * e2 + noise(random) * n);
  }
  const PlaneFit fit = fit_plane(points);
  ASSERT_TRUE(fit.ok);
  EXPECT_GT(std::abs(fit.normal.dot(n)), std::cos(0.01 * M_PI / 180.0));  // within 0.01 deg
  EXPECT_NEAR(n.dot(fit.point - Eigen::Vector3d(3, 4, 5)), 0.0, 0.001);
  EXPECT_NEAR(fit.rms_mm, 0.01, 0.0005);
  // Collinear points determine no plane.
  EXPECT_FALSE(fit_plane({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}}).ok);
  EXPECT_FALSE(fit_plane({{0, 0, 0}, {1, 0, 0}}).ok);
}

TEST(Form, SphereFromACapIsItsCentreAndRadius) {
  std::mt19937_64 random(2);
  std::normal_distribution<double> gauss(0.0, 1.0), noise(0.0, 0.005);
  const Eigen::Vector3d centre(10, -5, 3);
  std::vector<Eigen::Vector3d> points;
  while (points.size() < 4000) {
    Eigen::Vector3d d(gauss(random), gauss(random), gauss(random));
    d.normalize();
    if (d.z() < 0.5) continue;  // a cap of 60 deg half-angle
    points.push_back(centre + (25.0 + noise(random)) * d);
  }
  const SphereFit fit = fit_sphere(points);
  ASSERT_TRUE(fit.ok);
  EXPECT_NEAR(fit.radius_mm, 25.0, 0.002);
  EXPECT_LT((fit.centre - centre).norm(), 0.004);
  EXPECT_NEAR(fit.rms_mm, 0.005, 0.0005);
  // Points on a circle (a plane) determine no sphere.
  std::vector<Eigen::Vector3d> circle;
  for (int i = 0; i < 50; ++i) circle.emplace_back(std::cos(0.1 * i), std::sin(0.1 * i), 0.0);
  EXPECT_FALSE(fit_sphere(circle).ok);
}

TEST(Form, ZoneTrimsHalfTheShareAtEachEnd) {
  std::vector<double> r;
  for (int i = 0; i <= 100; ++i) r.push_back(0.01 * i);  // 0 .. 1, 101 values
  r.push_back(std::numeric_limits<double>::quiet_NaN());
  const FormZone z = form_zone(r, 0.02);  // the 1st and the 99th percentile
  EXPECT_EQ(z.count, 101u);
  EXPECT_NEAR(z.lower_mm, 0.01, 1e-12);
  EXPECT_NEAR(z.upper_mm, 0.99, 1e-12);
  EXPECT_NEAR(z.width_mm, 0.98, 1e-12);
  EXPECT_NEAR(z.full_width_mm, 1.0, 1e-12);
  EXPECT_NEAR(form_zone(r, 0.0).width_mm, 1.0, 1e-12);
  EXPECT_EQ(form_zone({}, 0.01).width_mm, 0.0);
}

}  // namespace
}  // namespace conform
