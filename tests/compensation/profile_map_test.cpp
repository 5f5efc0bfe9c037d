#include "conform/compensation/profile_map.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

// A straight edge along +x, 1000 mm: C(t) = (1000 t, 0, 0).
ProfileEdgeCurve straight_edge(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  return ProfileEdgeCurve::cubic(PolynomialCurve::from_power_coefficients({offset, Eigen::Vector3d(1000.0, 0.0, 0.0)}));
}

// A circular arc edge in the xy plane, radius R, from the origin towards +x bending to +y: exact positions known.
ProfileEdgeCurve arc_edge(double R, double angle) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 400; ++i) {
    const double phi = angle * i / 400.0;
    points.emplace_back(R * std::sin(phi), R * (1.0 - std::cos(phi)), 0.0);
  }
  ProfileEdgeFitOptions options;
  options.model = ProfileEdgeModel::kSpline;
  options.noise_mm = 1e-6;
  options.knot_spacing_mm = 5.0;  // the automatic 20 mm (for scans with noise) leaves 1e-5 mm on this exact arc
  return fit_profile_edge(points, options).curve;
}

TEST(ProfileMap, StraightEdgeIsTheIdentityWithGlobalZ) {
  const ProfileMap map(straight_edge(), Eigen::Vector3d(0.0, 0.0, 5.0));  // any length
  const ProfileMappedPoint p = map.map(100.0, 250.0);
  // Eq. (4)-(6): V1 = Z x C' = z x x = y.
  EXPECT_LT((p.position - Eigen::Vector3d(250.0, 100.0, 0.0)).norm(), 1e-9);
  EXPECT_LT((p.across - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_NEAR(p.t, 0.25, 1e-12);
  EXPECT_LE(std::abs(p.arc_length_residual_mm), 1e-8);
  EXPECT_THROW(map.map(0.0, 1000.5), Error);
  EXPECT_THROW(ProfileMap(straight_edge(), Eigen::Vector3d::Zero()), Error);
  // Z along the edge: no direction across it.
  EXPECT_THROW(ProfileMap(straight_edge(), Eigen::Vector3d::UnitX()).map(1.0, 10.0), Error);
}

TEST(ProfileMap, ArcEdgeMapsAlongTheRadius) {
  // On an arc of radius R, (Tx, Ty) lands at angle Ty / R, at distance R - Tx from the centre (0, R): exact.
  const double R = 5000.0;
  const ProfileMap map(arc_edge(R, 0.3), Eigen::Vector3d::UnitZ());
  for (double ty : {0.0, 400.0, 777.0, 1400.0}) {
    const double phi = ty / R, tx = 120.0;
    const Eigen::Vector3d expected((R - tx) * std::sin(phi), R - (R - tx) * std::cos(phi), 0.0);
    // Inside, the fit of the exact arc is good to 1e-6 mm; at the very end the spline's bending energy (no
    // curvature at its ends) tilts the tangent by ~2e-5 rad, 2 um at Tx = 120 mm.
    EXPECT_LT((map.map(tx, ty).position - expected).norm(), ty == 0.0 ? 0.01 : 1e-6) << ty;
  }
}

TEST(ProfileMap, SecondEdgeGivesTheLocalWebDirection) {
  // The web twisted by 30 degrees about the edge: the second edge at (s, W cos 30, W sin 30).
  const double W = 370.0, angle = M_PI / 6.0;
  const Eigen::Vector3d across(0.0, std::cos(angle), std::sin(angle));
  const ProfileMap local(straight_edge(), straight_edge(W * across));
  ASSERT_TRUE(local.local());
  const ProfileMappedPoint p = local.map(100.0, 500.0);
  EXPECT_LT((p.across - across).norm(), 1e-9);
  EXPECT_NEAR(p.local_width_mm, W, 1e-9);
  EXPECT_LT((p.position - (Eigen::Vector3d(500.0, 0.0, 0.0) + 100.0 * across)).norm(), 1e-7);
}

TEST(ProfileMap, WebNormalOfAPlanarBowIsItsPlane) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 100; ++i) {
    const double u = i / 100.0;
    points.emplace_back(12000.0 * u, 40.0 * 4.0 * u * (1.0 - u), 0.0);
  }
  const ProfileWebNormal z = fit_profile_web_normal(points);
  EXPECT_LT((z.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);  // oriented towards +z
  EXPECT_GT(z.flatness_ratio, 1e6);
  // A straight edge with noise of equal size across it in y and z has no plane.
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i].y() = 1e-3 * std::sin(1.7 * static_cast<double>(i));
    points[i].z() = 1e-3 * std::cos(2.9 * static_cast<double>(i));
  }
  EXPECT_THROW(fit_profile_web_normal(points), Error);
}

}  // namespace
}  // namespace conform
