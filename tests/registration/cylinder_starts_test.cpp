// The coarse starts from fitted cylinder axes (cylinder_starts.h), against a tube arc in a known frame.

#include "cylinder_starts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

#include "conform/core/random.h"
#include "registration_test_util.h"

namespace conform {
namespace {

// A tube of radius r along z, z in [0, 300], its outer wall over azimuths [0, to_deg) at one point about every
// `step` mm, each moved along its normal by Gaussian noise of 0.02 mm (seeded).
std::vector<Eigen::Vector3d> tube(double r, double to_deg, double step, std::uint64_t seed) {
  Random random(seed);
  std::vector<Eigen::Vector3d> out;
  for (double phi = 0.0; phi < to_deg * M_PI / 180.0; phi += step / r) {
    for (double z = 0.0; z <= 300.0; z += step) {
      const double rr = r + 0.02 * random.normal();
      out.emplace_back(rr * std::cos(phi), rr * std::sin(phi), z);
    }
  }
  return out;
}

std::vector<Eigen::Vector3d> radial_normals(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : points) out.push_back(Eigen::Vector3d(p.x(), p.y(), 0.0).normalized());
  return out;
}

// A 120 deg arc of the whole length, moved into another frame: its axis is laid on the reference's both ways, its
// ends at the tube's (they agree: one placement), turned in steps of 4 mm at its wall (R100: 360 / 2.29 deg = 158
// turns a way, every start marked for screening). One start lies within half a step of the truth (the turn) and
// within half a step's arc plus 0.5 mm (the fits) at the scan's centre (seen: 0.81 deg, 1.16 mm): the one a quick probe
// finishes.
TEST(CylinderStarts, OneStartLiesWithinHalfAStepOfTheTruth) {
  const std::vector<Eigen::Vector3d> reference = tube(100.0, 360.0, 3.0, 1);
  Random random(5);
  const Eigen::Isometry3d truth = test::random_motion(random, M_PI, 200.0, Eigen::Vector3d::Zero());
  const std::vector<Eigen::Vector3d> scan = test::transformed_points(tube(100.0, 120.0, 2.0, 2), truth.inverse());
  const std::vector<CoarseStart> starts = detail::cylinder_starts(scan, reference, radial_normals(reference), 4.0);
  const double step_deg = 4.0 / 100.0 * 180.0 / M_PI;
  ASSERT_EQ(starts.size(), 2u * static_cast<std::size_t>(std::ceil(360.0 / step_deg)));
  const Eigen::Vector3d centre = test::mean_point(scan);
  double best_deg = std::numeric_limits<double>::infinity(), best_mm = best_deg;
  for (const CoarseStart& s : starts) {
    EXPECT_TRUE(s.screen);
    EXPECT_EQ(s.label.rfind("cylinder axis ", 0), 0u);
    const double deg = test::rotation_error_deg(s.T_ref_scan, truth);
    if (deg < best_deg) {
      best_deg = deg;
      best_mm = (s.T_ref_scan * centre - truth * centre).norm();
    }
  }
  std::printf("nearest start: %.3f deg, %.3f mm at the centre\n", best_deg, best_mm);
  EXPECT_LT(best_deg, 0.5 * step_deg + 0.2);
  EXPECT_LT(best_mm, 2.0 + 0.5);
}

// No starts where there is no cylinder to lay on another: radii 100 and 150 mm (beyond 10 % apart), or a plane.
TEST(CylinderStarts, NoneWhenTheRadiiDifferOrThereIsNoCylinder) {
  const std::vector<Eigen::Vector3d> reference = tube(150.0, 360.0, 3.0, 1);
  EXPECT_TRUE(detail::cylinder_starts(tube(100.0, 120.0, 2.0, 2), reference, radial_normals(reference), 4.0).empty());
  std::vector<Eigen::Vector3d> plane;
  for (double x = 0.0; x < 100.0; x += 2.0) {
    for (double y = 0.0; y < 100.0; y += 2.0) plane.emplace_back(x, y, 0.0);
  }
  EXPECT_TRUE(detail::cylinder_starts(plane, reference, radial_normals(reference), 4.0).empty());
}

}  // namespace
}  // namespace conform
