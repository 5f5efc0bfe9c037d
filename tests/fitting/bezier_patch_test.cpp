// A bicubic Bézier patch: subdivision reproduces it, its control-point box contains it (convex hull), exact
// derivatives of a polynomial patch, affine invariance.

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "conform/fitting/bezier_network.h"
#include "conform/fitting/surface_grid.h"
#include "wavy_grid.h"

namespace conform {
namespace {

using test::wavy;
using test::wavy_grid;

TEST(BezierPatch, SubdivisionReproducesTheSurface) {
  const BezierPatch patch = BezierNetwork(wavy_grid(5, 5)).patch(1, 2);
  for (const auto& [su, sv] : {std::make_pair(0.5, 0.5), std::make_pair(0.3, 0.8)}) {
    const std::array<BezierPatch, 4> q = patch.subdivide(su, sv);
    for (double a = 0.0; a <= 1.0; a += 0.25) {
      for (double b = 0.0; b <= 1.0; b += 0.25) {
        EXPECT_LT((q[0].position(a, b) - patch.position(a * su, b * sv)).norm(), 1e-12);
        EXPECT_LT((q[1].position(a, b) - patch.position(su + a * (1 - su), b * sv)).norm(), 1e-12);
        EXPECT_LT((q[2].position(a, b) - patch.position(a * su, sv + b * (1 - sv))).norm(), 1e-12);
        EXPECT_LT((q[3].position(a, b) - patch.position(su + a * (1 - su), sv + b * (1 - sv))).norm(), 1e-12);
        // The chain rule: d/da of q[3] is (1 - su) r_u.
        EXPECT_LT((q[3].derivative(a, b, 1, 0) - (1 - su) * patch.derivative(su + a * (1 - su), sv + b * (1 - sv), 1, 0)).norm(), 1e-10);
      }
    }
  }
  const Eigen::AlignedBox3d box = patch.bounds();
  for (double a = 0.0; a <= 1.0; a += 0.1) {
    for (double b = 0.0; b <= 1.0; b += 0.1) EXPECT_TRUE(box.contains(patch.position(a, b)));  // convex hull
  }
}

TEST(BezierPatch, BoundsInARotatedFrameAndTransformed) {
  const BezierPatch patch = BezierNetwork(wavy_grid(5, 5)).patch(2, 1);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(5, -3, 2);
  const BezierPatch moved = patch.transformed(R, t);
  const Eigen::AlignedBox3d box = patch.bounds(R);
  for (double a = 0.0; a <= 1.0; a += 0.1) {
    for (double b = 0.0; b <= 1.0; b += 0.1) {
      EXPECT_LT((moved.position(a, b) - (R * patch.position(a, b) + t)).norm(), 1e-12);  // affine invariance
      EXPECT_TRUE(box.contains(R * patch.position(a, b)));
    }
  }
}

TEST(BezierPatch, DerivativesMatchAParaboloidExactly) {
  const auto f = [](double u, double v) { return Eigen::Vector3d(10 * u, 10 * v, 3 * u * u + 2 * u * v - v * v); };
  const BezierPatch p = interpolating_patch(f);
  for (double u = 0.0; u <= 1.0; u += 0.2) {
    for (double v = 0.0; v <= 1.0; v += 0.2) {
      EXPECT_LT((p.position(u, v) - f(u, v)).norm(), 1e-12);
      EXPECT_LT((p.derivative(u, v, 1, 0) - Eigen::Vector3d(10, 0, 6 * u + 2 * v)).norm(), 1e-11);
      EXPECT_LT((p.derivative(u, v, 0, 1) - Eigen::Vector3d(0, 10, 2 * u - 2 * v)).norm(), 1e-11);
      EXPECT_LT((p.derivative(u, v, 2, 0) - Eigen::Vector3d(0, 0, 6)).norm(), 1e-10);
      EXPECT_LT((p.derivative(u, v, 1, 1) - Eigen::Vector3d(0, 0, 2)).norm(), 1e-10);
      EXPECT_LT((p.derivative(u, v, 0, 2) - Eigen::Vector3d(0, 0, -2)).norm(), 1e-10);
    }
  }
}

}  // namespace
}  // namespace conform
