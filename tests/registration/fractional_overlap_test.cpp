// Fractional ICP's overlap (registration/src/pairs.h, fractional_overlap; Phillips, Liu & Tomasi 2007) against
// generated distances whose overlap is known, and ICP started at the truth on a scan half of which is not on the
// reference (a room scan's other half): with the overlap estimated the right start is kept; with every pair kept
// (overlap 1) the other half pulls it away.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "conform/core/mesh.h"
#include "conform/core/random.h"
#include "conform/registration/icp.h"
#include "pairs.h"
#include "registration_test_util.h"

namespace conform {
namespace {

std::vector<detail::Pair> pairs_of(std::size_t near, std::size_t far, std::size_t missing, std::uint64_t seed) {
  Random random(seed);
  std::vector<detail::Pair> pairs;
  for (std::size_t i = 0; i < near; ++i) {
    detail::Pair p;
    p.found = true;
    p.distance = std::abs(0.02 * random.normal());
    pairs.push_back(p);
  }
  for (std::size_t i = 0; i < far; ++i) {
    detail::Pair p;
    p.found = true;
    p.distance = random.uniform(5.0, 200.0);
    pairs.push_back(p);
  }
  pairs.resize(pairs.size() + missing);  // not found: beyond the maximum distance
  return pairs;
}

// 60 % of the pairs at the noise (0.02 mm), 40 % 5-200 mm away: 0.60 within 0.01 on five seeds; all at the noise:
// at least 0.95 (the noise's own tail is kept); pairs not found count in the scan's size; none found: 0.
TEST(FractionalOverlap, FindsTheShareAtTheNoise) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    EXPECT_NEAR(detail::fractional_overlap(pairs_of(600, 400, 0, seed), 0.05, 3.0), 0.6, 0.01) << seed;
    EXPECT_GE(detail::fractional_overlap(pairs_of(1000, 0, 0, seed), 0.05, 3.0), 0.95) << seed;
    EXPECT_NEAR(detail::fractional_overlap(pairs_of(500, 0, 500, seed), 0.05, 3.0), 0.5, 0.03) << seed;
  }
  EXPECT_EQ(detail::fractional_overlap(pairs_of(0, 0, 10, 1), 0.05, 3.0), 0.0);
  // Never below the floor, even when the far pairs are most of the scan.
  EXPECT_GE(detail::fractional_overlap(pairs_of(10, 990, 0, 1), 0.3, 3.0), 0.3);
}

// A room corner (floor and two walls, 200 mm, 0.05 mm noise) as reference; the scan holds the corner and, as much
// again, a slanted wall 20-60 mm off the reference that the reference does not have. Started at the truth with a
// 100 mm maximum distance: estimating the overlap keeps the start (within 3 std, 0.1 mm and 0.02 deg; measured
// 0.045 mm and 0.011 deg at a std of 0.049 mm); every pair kept, the slanted wall pulls it 7.7 deg and 17 mm away.
TEST(FractionalOverlap, IcpKeepsARightStartWithHalfTheScanOffTheReference) {
  Random random(7);
  std::vector<Eigen::Vector3d> reference, scan;
  const auto corner = [&](std::vector<Eigen::Vector3d>& out, std::size_t n, double noise) {
    for (std::size_t i = 0; i < n; ++i) {
      const double u = random.uniform(0.0, 200.0), v = random.uniform(0.0, 200.0), e = noise * random.normal();
      switch (i % 3) {
        case 0:
          out.emplace_back(u, v, e);
          break;
        case 1:
          out.emplace_back(e, u, v);
          break;
        default:
          out.emplace_back(u, e, v);
          break;
      }
    }
  };
  corner(reference, 30000, 0.0);
  corner(scan, 6000, 0.05);
  for (int i = 0; i < 6000; ++i) {  // the other half: a wall the reference does not have
    const double u = random.uniform(0.0, 200.0), v = random.uniform(0.0, 200.0);
    scan.emplace_back(100.0 + 0.2 * u, u, 20.0 + 0.2 * v + 0.05 * random.normal());
  }
  Mesh reference_mesh;
  reference_mesh.vertices = reference;
  const IcpReference ref(reference_mesh);
  IcpOptions options;
  options.max_correspondence_distance_mm = 100.0;
  options.estimate_overlap = true;
  const IcpResult estimated = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
  options.estimate_overlap = false;
  const IcpResult all = icp(scan, ref, Eigen::Isometry3d::Identity(), options);
  const auto moved = [](const IcpResult& r) {
    return std::make_pair(test::rotation_error_deg(r.T_ref_scan, Eigen::Isometry3d::Identity()),
                          test::translation_error_mm(r.T_ref_scan, Eigen::Isometry3d::Identity()));
  };
  const auto [deg, mm] = moved(estimated);
  const auto [all_deg, all_mm] = moved(all);
  std::printf("estimated overlap %.3f: moved %.5f deg %.5f mm (std %.5f mm); every pair: %.4f deg %.4f mm\n",
              estimated.inlier_fraction, deg, mm, estimated.degeneracy.std.tail<3>().maxCoeff(), all_deg, all_mm);
  EXPECT_NEAR(estimated.inlier_fraction, 0.5, 0.05);
  EXPECT_LT(deg, 0.02);
  EXPECT_LT(mm, 0.1);
  EXPECT_LT(mm, 3.0 * estimated.degeneracy.std.tail<3>().maxCoeff() + 1e-3);
  EXPECT_GT(all_deg + all_mm, 10.0 * (deg + mm));
}

}  // namespace
}  // namespace conform
