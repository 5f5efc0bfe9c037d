// The FPFH support against thin walls scanned from one side: a part of 10 mm plates (a base, an upright and two ribs
// of different heights), the reference sampled on every face, the scan only on the faces that look towards the
// scanner. At the default support (5 voxels, about 19 mm here) a reference histogram also holds the far face of the
// plate, which the scan never sees, so few features are mutual nearest neighbours; fpfh_ransac then computes them
// again at the narrow radius (2.5 voxels), and the coarse stage lands on the true pose.

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/mesh.h"
#include "conform/core/random.h"
#include "conform/registration/coarse.h"
#include "conform/registration/icp_reference.h"
#include "plates_part.h"
#include "registration_test_util.h"

namespace conform {
namespace {

TEST(FpfhSupport, ANarrowerSupportMatchesAOneSideScanOfThinPlates) {
  Random random(5);
  const std::vector<Eigen::Vector3d> reference = test::plates_surface(10.0, 1.0, 0.0, Eigen::Vector3d::Zero(), random);
  Mesh reference_mesh;
  reference_mesh.vertices = reference;
  const Eigen::Vector3d towards_scanner(0.3, 0.7, 0.65);
  int right = 0;
  const int trials = 4;
  for (int trial = 0; trial < trials; ++trial) {
    const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 100.0, Eigen::Vector3d(60, 30, 30));
    const std::vector<Eigen::Vector3d> scan =
        test::transformed_points(test::plates_surface(10.0, 1.0, 0.03, towards_scanner, random), truth.inverse());
    FpfhOptions options;
    options.seed = static_cast<std::uint64_t>(trial + 1);
    const FpfhResult wide_only = [&] {
      FpfhOptions o = options;
      o.narrow_feature_radius = 0.0;
      return fpfh_ransac(scan, reference, o);
    }();
    CoarseOptions coarse;
    coarse.method = CoarseMethod::kFpfh;
    coarse.fpfh = options;
    coarse.multi_start.probe.max_correspondence_distance_mm = 15.0;
    const CoarseResult c = coarse_align(scan, IcpReference(reference_mesh), coarse);
    const FpfhResult& r = c.fpfh;
    const double deg = test::rotation_error_deg(c.T_ref_scan, truth);
    const Eigen::Vector3d at = truth.inverse() * Eigen::Vector3d(60, 30, 30);
    const double mm = (c.T_ref_scan * at - truth * at).norm();
    std::printf(
        "trial %d: voxel %.2f mm; at %.1f mm %zu of %zu matches pass the filters, at %.1f mm %zu; coarse pose "
        "%.4f deg, %.4f mm off%s\n",
        trial, r.voxel_mm, wide_only.feature_radius_mm, wide_only.filtered_points, wide_only.scan_points,
        r.feature_radius_mm, r.filtered_points, deg, mm, c.ranking.ambiguous ? ", ambiguous" : "");
    // The cause: at the wide support too few features match both ways, and the narrow support is used.
    EXPECT_LT(wide_only.filtered_points, options.min_matched_points);
    EXPECT_NEAR(r.feature_radius_mm, options.narrow_feature_radius * r.voxel_mm, 1e-9);
    EXPECT_GT(r.filtered_points, 2 * options.min_matched_points);
    // The coarse stage's pose (the best hypothesis after its short ICP and refinement), unambiguous: the truth within
    // 0.05 deg and half the reference's 1 mm point spacing.
    right += deg < 0.05 && mm < 0.5 && !c.ranking.ambiguous;
  }
  EXPECT_EQ(right, trials);
}

TEST(FpfhSupport, TheNarrowRadiusIsValidatedAgainstTheWideOne) {
  FpfhOptions options;
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.narrow_feature_radius = 0.0;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  options.narrow_feature_radius = options.feature_radius;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("narrow_feature_radius"), std::string::npos) << why;
  options.narrow_feature_radius = 1.0;
  EXPECT_FALSE(options.IsValid(&why));
}

}  // namespace
}  // namespace conform
