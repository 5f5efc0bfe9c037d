#include "conform/datasets/profile_deformation.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {
namespace {

ProfileDeformationOptions straight() {
  ProfileDeformationOptions o;
  o.length_mm = 6000.0;
  o.bow_in_plane_mm = 0.0;
  return o;
}

TEST(ProfileDeformation, NoDeformationIsTheFlatProfile) {
  const ProfileDeformation shape(straight());
  for (double ty : {0.0, 17.5, 3000.0, 6000.0}) {
    EXPECT_LT((shape.map(120.0, ty) - Eigen::Vector3d(ty, 120.0, 0.0)).norm(), 1e-9) << ty;
  }
}

TEST(ProfileDeformation, InPlaneBowIsTheEdgeOffsetExactly) {
  ProfileDeformationOptions o = straight();
  o.bow_in_plane_mm = 40.0;
  o.bow_asymmetry = 0.5;
  const ProfileDeformation shape(o);
  for (double s : {0.0, 1000.0, 3000.0, 5123.0, 6000.0}) {
    const double u = s / o.length_mm;
    const double v = 40.0 * 4.0 * u * (1.0 - u) * (1.0 + 0.5 * (2.0 * u - 1.0));
    // theta = asin(v'), so y(s) = integral of sin(theta) = v(s): to the quadrature's accuracy.
    EXPECT_NEAR(shape.edge(s).y(), v, 1e-7) << s;
    EXPECT_NEAR(shape.edge(s).z(), 0.0, 1e-12);
  }
  // The edge keeps its length: a fine polyline along it is L long (its chords shorten it by ~L h^2 k^2 / 24).
  double length = 0.0;
  for (int k = 1; k <= 6000; ++k) length += (shape.edge(k) - shape.edge(k - 1.0)).norm();
  EXPECT_NEAR(length, 6000.0, 1e-6);
  EXPECT_LT(shape.edge(6000.0).x(), 6000.0 - 0.1);  // so the bowed edge ends short of x = L
}

TEST(ProfileDeformation, OutOfPlaneBowTwistAndKink) {
  ProfileDeformationOptions o = straight();
  o.bow_out_of_plane_mm = 25.0;
  EXPECT_NEAR(ProfileDeformation(o).edge(3000.0).z(), 25.0, 1e-7);

  o = straight();
  o.twist_rad = 0.1;
  const Eigen::Matrix3d end = ProfileDeformation(o).frame(6000.0);
  EXPECT_LT((end.col(1) - Eigen::Vector3d(0.0, std::cos(0.1), std::sin(0.1))).norm(), 1e-12);
  EXPECT_LT((end.transpose() * end - Eigen::Matrix3d::Identity()).norm(), 1e-12);

  o = straight();
  o.kink_rad = 0.02;
  o.kink_at_mm = 2000.0;
  o.kink_length_mm = 100.0;
  const ProfileDeformation kinked(o);
  const double turn = std::acos(kinked.frame(1949.0).col(0).dot(kinked.frame(2051.0).col(0)));
  EXPECT_NEAR(turn, 0.02, 1e-12);  // the whole bend inside [at - length/2, at + length/2]
  EXPECT_NEAR(kinked.edge(1900.0).y(), 0.0, 1e-9);
  EXPECT_NEAR(kinked.edge(4000.0).y(), 2000.0 * std::sin(0.02), 0.01);  // the bend's centre is at 2000 +- 0.5 mm
}

TEST(ProfileDeformation, StraighteningInvertsTheMap) {
  ProfileDeformationOptions o;
  o.bow_asymmetry = -0.4;
  o.bow_out_of_plane_mm = 20.0;
  o.twist_rad = 0.03;
  o.kink_rad = 0.01;
  const ProfileDeformation shape(o);
  Random random(4);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector2d design(random.uniform(0.0, 370.0), random.uniform(0.0, 12000.0));
    double off = 1.0;
    const Eigen::Vector2d back = shape.straighten(shape.map(design.x(), design.y()), &off);
    EXPECT_LT((back - design).norm(), 1e-6) << design.transpose();
    EXPECT_NEAR(off, 0.0, 1e-9);
  }
  // Off the web by 2 mm along B: straightened to the same design point, 2 mm off.
  const Eigen::Vector3d p = shape.map(100.0, 5000.0) + 2.0 * shape.frame(5000.0).col(2);
  double off = 0.0;
  EXPECT_LT((shape.straighten(p, &off) - Eigen::Vector2d(100.0, 5000.0)).norm(), 1e-6);
  EXPECT_NEAR(off, 2.0, 1e-9);
}

TEST(ProfileDeformation, RejectsBadOptions) {
  ProfileDeformationOptions o;
  o.bow_asymmetry = 1.5;
  EXPECT_THROW(ProfileDeformation{o}, Error);
  o = ProfileDeformationOptions{};
  o.length_mm = 0.0;
  EXPECT_FALSE(o.IsValid(nullptr));
  o = ProfileDeformationOptions{};
  o.kink_rad = 0.01;
  o.kink_at_mm = 13000.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("kink_at_mm"), std::string::npos);
}

}  // namespace
}  // namespace conform
