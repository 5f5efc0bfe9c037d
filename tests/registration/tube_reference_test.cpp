// The tube frame from the axis fit and markers: recovers a generated tube's T_tube_world, reports the marker
// residuals, and says that without markers rotation about and shift along the axis are free.

#include "conform/registration/tube_reference.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/datasets/tube.h"

namespace conform {
namespace {

constexpr double kPi = 3.141592653589793;

struct Scene {
  TubeScan scan;
  std::vector<Eigen::Vector3d> normals;
  std::vector<Eigen::Vector3d> markers_tube;
  std::vector<Eigen::Vector3d> markers_scan;
};

Scene scene() {
  TubeOptions t;
  t.radius_mm = 500.0;
  t.length_mm = 600.0;
  t.arc_rad = 2.0;
  t.edge_mm = 12.0;
  t.noise_mm = 0.05;
  t.vertex_normals = true;
  t.T_world_tube = tube_frame({120.0, -40.0, 300.0}, {0.2, 0.9, 0.3}, {1.0, 0.0, 0.0});
  Scene s;
  s.scan = generate_tube(t);
  s.normals = s.scan.mesh.normals;
  // A non-symmetric layout of punch marks on the surface: (azimuth, z).
  for (const auto& [az, z] :
       std::vector<std::pair<double, double>>{{-0.6, -200.0}, {0.1, 50.0}, {0.7, 180.0}, {0.3, -90.0}}) {
    const Eigen::Vector3d m(500.0 * std::cos(az), 500.0 * std::sin(az), z);
    s.markers_tube.push_back(m);
    s.markers_scan.push_back(t.T_world_tube * m);
  }
  return s;
}

TEST(TubeReference, AxisFitPlusMarkersRecoversTheTubeFrame) {
  const Scene s = scene();
  const TubeReferenceResult r = tube_reference(s.scan.mesh.vertices, s.normals, s.markers_scan, s.markers_tube);
  ASSERT_TRUE(r.ok) << r.termination;
  EXPECT_FALSE(r.free_about_axis);
  const Eigen::Isometry3d truth = s.scan.truth.T_world_tube.inverse();
  // The axis fit on 0.05 mm noise over a 1000 mm x 600 mm patch: its direction to ~1e-4 rad, its position to ~0.05 mm;
  // the markers then sit within ~0.1 mm of their known places.
  const Eigen::AngleAxisd error(r.T_tube_scan.linear() * truth.linear().transpose());
  EXPECT_LT(std::abs(error.angle()), 3e-4);
  for (const Eigen::Vector3d& p : s.markers_scan) EXPECT_LT((r.T_tube_scan * p - truth * p).norm(), 0.2);
  ASSERT_EQ(r.marker_residuals_mm.size(), 4u);
  EXPECT_LT(r.marker_max_mm, 0.2);
  EXPECT_GT(r.marker_max_mm, 0.0);
}

TEST(TubeReference, WithoutMarkersTheAxisIsFoundAndTheRestIsSaidToBeFree) {
  const Scene s = scene();
  const TubeReferenceResult r = tube_reference(s.scan.mesh.vertices, s.normals, {}, {});
  ASSERT_TRUE(r.ok) << r.termination;
  EXPECT_TRUE(r.free_about_axis);
  EXPECT_NE(r.termination.find("free"), std::string::npos);
  // The tube's axis maps to +-z.
  const Eigen::Vector3d axis_world = s.scan.truth.T_world_tube.linear().col(2);
  EXPECT_GT(std::abs((r.T_tube_scan.linear() * axis_world).z()), 1.0 - 1e-7);
}

TEST(TubeReference, AMisplacedMarkerFailsWithItsResidual) {
  Scene s = scene();
  s.markers_scan[2] += Eigen::Vector3d(0.0, 0.0, 8.0);
  const TubeReferenceResult r = tube_reference(s.scan.mesh.vertices, s.normals, s.markers_scan, s.markers_tube);
  EXPECT_FALSE(r.ok);
  EXPECT_GT(r.marker_max_mm, 2.0);
}

TEST(TubeReference, TwoMarkersOrMarkersOnTheAxisAreErrors) {
  const Scene s = scene();
  const std::vector<Eigen::Vector3d> two(s.markers_scan.begin(), s.markers_scan.begin() + 2);
  const std::vector<Eigen::Vector3d> two_tube(s.markers_tube.begin(), s.markers_tube.begin() + 2);
  EXPECT_THROW(tube_reference(s.scan.mesh.vertices, s.normals, two, two_tube), Error);
  const std::vector<Eigen::Vector3d> on_axis = {{0, 0, 1}, {0, 0, 2}, {0, 0, 3}};
  EXPECT_THROW(tube_frame_from_markers(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), on_axis, on_axis, nullptr),
               Error);
}

}  // namespace
}  // namespace conform
