// step_sums (registration/src/step_sums.h): the one-pass sums about an arbitrary origin, moved to the pairs' centroid,
// equal the sums taken directly about the centroid (plane_matrix.h and the Gauss-Newton normal equations).

#include "step_sums.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "plane_matrix.h"

namespace conform {
namespace {

struct Item {
  Eigen::Vector3d q, n;
  double r, w;
};

std::vector<Item> random_items(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Item> items(count);
  for (std::size_t k = 0; k < count; ++k) {
    Item& it = items[k];
    it.q = Eigen::Vector3d(100.0 + 60.0 * u(rng), -40.0 + 30.0 * u(rng), 5.0 * u(rng));
    it.n = Eigen::Vector3d(0.3 * u(rng), 0.3 * u(rng), 1.0).normalized();
    it.r = 0.05 * u(rng);
    // Most weights 1 (Huber inliers), some down-weighted, a few zero.
    it.w = k % 7 == 0 ? 0.5 + 0.5 * u(rng) : k % 31 == 0 ? 0.0 : 1.0;
  }
  return items;
}

double relative_difference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).norm() / std::max(b.norm(), 1e-300);
}

TEST(StepSums, EqualTheDirectSumsAboutTheCentroid) {
  for (const std::size_t count : {std::size_t{50}, std::size_t{40000}}) {  // one block, and several in parallel
    const std::vector<Item> items = random_items(count, 7);
    const auto item = [&](std::size_t k, Eigen::Vector3d& q, Eigen::Vector3d& n, double& r, double& w) {
      q = items[k].q;
      n = items[k].n;
      r = items[k].r;
      w = items[k].w;
    };
    // The origin far from the pairs (the scan's frame origin): the move to the centroid is exact in real numbers.
    const detail::StepSums sums = detail::step_sums(count, Eigen::Vector3d(-500.0, 300.0, 20.0), item);
    const PlaneNormalMatrix direct = detail::plane_normal_matrix_of(
        count, [&](std::size_t k) -> const Eigen::Vector3d& { return items[k].q; },
        [&](std::size_t k) -> const Eigen::Vector3d& { return items[k].n; }, [&](std::size_t k) { return items[k].r; });
    EXPECT_LT((sums.plane.centre - direct.centre).norm(), 1e-9);
    EXPECT_NEAR(sums.plane.length_scale_mm, direct.length_scale_mm, 1e-9 * direct.length_scale_mm);
    EXPECT_EQ(sums.plane.count, count);
    EXPECT_LT(relative_difference(sums.plane.H, direct.H), 1e-9);
    EXPECT_TRUE(sums.plane.residual_moment.isZero());
    // The weighted normal equations, J = [((q - c) x n) / L; n] (Chen & Medioni 1992), and the RMS; the robust
    // sandwich's middle sum (w r)^2 J J^T and its bread: sum J J^T over the pairs of weight 1 (Huber's psi' = 0
    // beyond its scale), sum w J J^T for a kernel that does not saturate.
    Matrix6d H = Matrix6d::Zero(), middle = Matrix6d::Zero(), huber_bread = Matrix6d::Zero();
    Vector6d g = Vector6d::Zero();
    double r2 = 0.0;
    for (const Item& it : items) {
      Vector6d J;
      J.head<3>() = (it.q - direct.centre).cross(it.n) / direct.length_scale_mm;
      J.tail<3>() = it.n;
      H += it.w * J * J.transpose();
      g += it.w * it.r * J;
      r2 += it.r * it.r;
      middle += (it.w * it.r) * (it.w * it.r) * J * J.transpose();
      if (it.w >= 1.0) huber_bread += J * J.transpose();
    }
    const double n = static_cast<double>(count);
    PlaneNormalMatrix huber = sums.plane, weighted = sums.plane;
    detail::residual_moments_of(count, true, huber, item);
    detail::residual_moments_of(count, false, weighted, item);
    EXPECT_LT(relative_difference(huber.residual_moment, middle / n), 1e-9);
    EXPECT_LT(relative_difference(weighted.residual_moment, middle / n), 1e-9);
    EXPECT_LT(relative_difference(huber.bread, huber_bread / n), 1e-9);
    EXPECT_LT(relative_difference(weighted.bread, H / n), 1e-9);
    // Unit weights: the middle is the plain residual moment and the bread the normal matrix.
    PlaneNormalMatrix plain = sums.plane;
    detail::residual_moments_of(count, true, plain, [&](std::size_t k, Eigen::Vector3d& q, Eigen::Vector3d& nk,
                                                        double& r, double& w) {
      item(k, q, nk, r, w);
      w = 1.0;
    });
    EXPECT_LT(relative_difference(plain.residual_moment, direct.residual_moment), 1e-9);
    EXPECT_LT(relative_difference(plain.bread, direct.H), 1e-9);
    EXPECT_LT(relative_difference(sums.H, H), 1e-9);
    EXPECT_LT(relative_difference(sums.g, g), 1e-9);
    EXPECT_NEAR(sums.rms_mm, std::sqrt(r2 / static_cast<double>(count)), 1e-12);
  }
}

TEST(StepSums, NoPairsGiveEmptySums) {
  const detail::StepSums sums = detail::step_sums(
      0, Eigen::Vector3d::Zero(), [](std::size_t, Eigen::Vector3d&, Eigen::Vector3d&, double&, double&) {});
  EXPECT_EQ(sums.plane.count, 0u);
  EXPECT_EQ(sums.plane.length_scale_mm, 0.0);
  EXPECT_TRUE(sums.H.isZero());
}

}  // namespace
}  // namespace conform
