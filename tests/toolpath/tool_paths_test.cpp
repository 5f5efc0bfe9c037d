// Eq. (5) groove interpolation, Eq. (7), (9), (11) tool poses, the local quadric fit and the seam refinement, against
// closed forms.

#include "conform/toolpath/intersection/tool_paths.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/toolpath/intersection/local_quadric.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

TEST(GrooveAngle, TakesTheGivenValuesAtTheQuartersAndInterpolatesBetween) {
  const std::array<double, 4> q = {0.1, 0.5, 0.3, 0.7};
  for (const auto mode : {GrooveInterpolation::kLinear, GrooveInterpolation::kQuadratic}) {
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(groove_angle(q, mode, i * kPi / 2), q[static_cast<std::size_t>(i)], 1e-15);
    EXPECT_NEAR(groove_angle(q, mode, 2.0 * kPi), q[0], 1e-15);  // cyclic
    EXPECT_NEAR(groove_angle(q, mode, -kPi / 2), q[3], 1e-15);
    // Halfway between two quarters both give the mean.
    EXPECT_NEAR(groove_angle(q, mode, 3.0 * kPi / 4), 0.4, 1e-15);
  }
  // A quarter of the way: linear 1/4, quadratic 2 (1/4)^2 = 1/8 of the rise.
  EXPECT_NEAR(groove_angle(q, GrooveInterpolation::kLinear, kPi / 8), 0.1 + 0.4 * 0.25, 1e-15);
  EXPECT_NEAR(groove_angle(q, GrooveInterpolation::kQuadratic, kPi / 8), 0.1 + 0.4 * 0.125, 1e-15);
}

TEST(ToolPaths, CuttingAndWeldingPosesFollowEquations7To11) {
  // A frame with n_s = x, n_l = -z (the T joint's toe): t = y, t_l_out = x.
  const PathFrame f = path_frame(0.0, {100, 0, 50}, {1, 0, 0}, {0, 0, -1});
  EXPECT_TRUE(f.tangent.isApprox(Eigen::Vector3d(0, 1, 0), 1e-15));
  EXPECT_TRUE(f.leg_out.isApprox(Eigen::Vector3d(1, 0, 0), 1e-15));
  ToolPathOptions options;
  options.groove_rad = {30 * kDeg, 0, 0, 0};
  options.weld_angle_rad = 40 * kDeg;
  options.cut_standoff_mm = 10.0;
  options.weld_standoff_mm = 20.0;
  const ToolPaths paths = tool_paths({f}, options);
  const Eigen::Vector3d d_c(std::cos(30 * kDeg), 0, -std::sin(30 * kDeg));
  const Eigen::Vector3d d_w(-std::cos(40 * kDeg), 0, std::sin(40 * kDeg));
  EXPECT_TRUE(paths.cut[0].direction.isApprox(d_c, 1e-14));
  EXPECT_TRUE(paths.weld[0].direction.isApprox(d_w, 1e-14));
  EXPECT_TRUE(paths.cut[0].position.isApprox(Eigen::Vector3d(100, 0, 50) - 10.0 * d_c, 1e-14));
  EXPECT_TRUE(paths.weld[0].position.isApprox(Eigen::Vector3d(100, 0, 50) - 20.0 * d_w, 1e-14));
  // A rotation about t: both directions stay perpendicular to it.
  EXPECT_NEAR(paths.cut[0].direction.dot(f.tangent), 0.0, 1e-15);
  EXPECT_NEAR(paths.weld[0].direction.dot(f.tangent), 0.0, 1e-15);
}

TEST(ToolPaths, ParallelNormalsAndBadOptionsAreErrors) {
  EXPECT_ANY_THROW(path_frame(0.0, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}));
  ToolPathOptions options;
  options.groove_rad[2] = 95 * kDeg;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("groove angle 3"), std::string::npos) << why;
  options = {};
  options.cut_standoff_mm = -1.0;
  EXPECT_ANY_THROW(tool_paths({}, options));
}

// Points of a cylinder of radius 200 about z near (200, 0, 0), the query point off their centroid: the quadric
// normal is the cylinder's normal at the query point; the plane (PCA) normal is the centroid's.
TEST(LocalQuadric, CylinderNormalAtAPointOffTheCentroid) {
  std::vector<Eigen::Vector3d> points;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j) {
      const double a = 0.02 * i + 0.01 * (j % 2);
      points.emplace_back(200 * std::cos(a), 200 * std::sin(a), 4.0 * j);
    }
  const double a = 0.045;
  const Eigen::Vector3d p(200 * std::cos(a), 200 * std::sin(a), 5.0);
  const Eigen::Vector3d truth(std::cos(a), std::sin(a), 0.0);
  TubeAxis axis;
  const Eigen::Vector3d quadric = pca_normal(points, p, axis, NormalFit::kQuadric);
  const Eigen::Vector3d plane = pca_normal(points, p, axis, NormalFit::kPlane);
  // The quadric misses the circle's 4th-order term, x^4 / (8 R^3) ~ 3e-4 mm over +-12 mm: 1e-3 deg, 2e-3 mm.
  EXPECT_LT(std::acos(std::min(1.0, quadric.dot(truth))), 1e-3 * kDeg);
  EXPECT_GT(std::acos(std::min(1.0, plane.dot(truth))), 1.0 * kDeg);  // the centroid is ~2.5 deg away
  const LocalQuadric patch = fit_local_quadric(points, p);
  EXPECT_TRUE(patch.quadric);
  EXPECT_NEAR(patch.height(p), 0.0, 2e-3);
  EXPECT_NEAR(std::abs(patch.height(p + 0.5 * truth)), 0.5, 2e-3);
}

// Two cylinders (the T joint, R 300 and r 150): a point pushed off the seam comes back onto it at its azimuth.
TEST(LocalQuadric, RefinementMovesAPointOntoBothSurfacesAtItsAzimuth) {
  const double R = 300.0;
  const double r = 150.0;
  const double phi = 0.6;
  // Stub about z (points r (cos, sin), z); leg about the x axis at z = 400: (y^2 + (z - 400)^2) = R^2.
  const auto stub_point = [&](double a, double z) { return Eigen::Vector3d(r * std::cos(a), r * std::sin(a), z); };
  const auto leg_point = [&](double x, double b) {
    return Eigen::Vector3d(x, R * std::sin(b), 400.0 - R * std::cos(b));
  };
  const double y = r * std::sin(phi);
  const double z = 400.0 - std::sqrt(R * R - y * y);
  const Eigen::Vector3d seam = stub_point(phi, z);
  std::vector<Eigen::Vector3d> stub;
  std::vector<Eigen::Vector3d> leg;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) {
      stub.push_back(stub_point(phi + 0.02 * i, z + 3.0 * j));
      leg.push_back(leg_point(seam.x() + 3.0 * i, std::asin(y / R) + 0.01 * j));
    }
  Eigen::Vector3d p = seam + Eigen::Vector3d(-0.8, 0.5, 1.2);
  const double azimuth = std::atan2(p.y(), p.x());
  ASSERT_TRUE(refine_seam_point(fit_local_quadric(stub, p), fit_local_quadric(leg, p), 3.0, &p));
  EXPECT_NEAR(std::atan2(p.y(), p.x()), azimuth, 1e-12);
  EXPECT_NEAR(p.head<2>().norm(), r, 1e-3);
  EXPECT_NEAR(std::hypot(p.y(), p.z() - 400.0), R, 1e-3);
}

}  // namespace
}  // namespace conform
