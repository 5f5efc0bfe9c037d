// Trajectory mapping: the place on the contour of a point (continuous between contour points), rigid and segment
// mapping against known transforms, tool normals fitted to a tilted plane scan, and bad trajectories rejected.

#include "conform/compensation/trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {
namespace {

Polyline circle(double r, int n) {
  Polyline c;
  c.closed = true;
  for (int i = 0; i < n; ++i) c.points.emplace_back(r * std::cos(2 * M_PI * i / n), r * std::sin(2 * M_PI * i / n), 0);
  return c;
}

TEST(Trajectory, LocatesPointsBetweenContourPoints) {
  Polyline line;
  for (int i = 0; i <= 10; ++i) line.points.emplace_back(10.0 * i, 0.0, 0.0);  // 10 mm apart
  const std::vector<double> s = arc_lengths(line);
  const std::vector<double> at = locate_on_contour(line, s, {{23.5, 1.0, 0.0}, {0.0, -2.0, 0.0}, {99.9, 3.0, 0.0}});
  EXPECT_NEAR(at[0], 23.5, 1e-9);  // orthogonal projection, not the nearest vertex (20)
  EXPECT_NEAR(at[1], 0.0, 1e-9);
  EXPECT_NEAR(at[2], 99.9, 1e-9);
}

TEST(Trajectory, RigidAndSegmentMappingsFollowTheirTransforms) {
  const Polyline c = circle(100.0, 720);
  Trajectory nominal;
  for (int i = 0; i < 90; ++i) {
    const double a = 2 * M_PI * (i + 0.5) / 90;
    nominal.points.emplace_back(100 * std::cos(a), 100 * std::sin(a), 0);
    nominal.normals.push_back(Eigen::Vector3d::UnitZ());
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(1, 2, 3);
  const Trajectory rigid = map_rigidly(nominal, T);
  const ContourSegmentation g = segment_contour(c, {});
  const Trajectory segments = map_by_segments(nominal, c, g, std::vector<Eigen::Isometry3d>(g.segments.size(), T));
  for (std::size_t i = 0; i < nominal.points.size(); ++i) {
    // All segments share T: blending changes nothing (to rounding).
    EXPECT_LT((rigid.points[i] - T * nominal.points[i]).norm(), 1e-12);
    EXPECT_LT((segments.points[i] - rigid.points[i]).norm(), 1e-9);
    EXPECT_LT((segments.normals[i] - T.linear() * Eigen::Vector3d::UnitZ()).norm(), 1e-9);
  }
  EXPECT_THROW(map_by_segments(nominal, c, g, {T}), Error);
}

TEST(Trajectory, ToolNormalsFromAPlaneScan) {
  // A plane tilted 10 degrees about x, sampled every 0.5 mm without noise: the fitted normal is exact to rounding.
  const Eigen::Vector3d n = Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = n.cross(u);
  std::vector<Eigen::Vector3d> scan;
  for (int i = -40; i <= 40; ++i) {
    for (int j = -40; j <= 40; ++j) scan.push_back(0.5 * i * u + 0.5 * j * v);
  }
  const KdTree tree(scan);
  Trajectory t;
  t.points = {Eigen::Vector3d(1, 2, 0).x() * u + 2.0 * v, Eigen::Vector3d(100, 100, 100)};
  t.normals = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()};  // 10 degrees off: within the 20 degree limit
  const std::size_t from_scan = reestimate_tool_normals(t, scan, tree, {});
  EXPECT_EQ(from_scan, 1u);  // the second point is far from the scan: it keeps its normal
  EXPECT_LT((t.normals[0] - n).norm(), 1e-9);
  EXPECT_EQ(t.normals[1], Eigen::Vector3d::UnitZ());
}

TEST(Trajectory, SmoothedToolNormalsLoseTheJitterNotTheTurn) {
  // A closed circle of radius 100 mm, rows 1 mm apart, normals tilted outwards by 20 degrees (they turn 0.57 degrees
  // per row with the circle), each jittered by a seeded +-0.5 degrees: the 10 mm window leaves the turn and removes
  // most of the jitter.
  const int n = 628;
  Trajectory t;
  std::vector<Eigen::Vector3d> truth;
  std::uint64_t state = 7;
  const auto jitter = [&]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * M_PI / 180.0;
  };
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * i / n;
    const Eigen::Vector3d radial(std::cos(a), std::sin(a), 0.0);
    t.points.push_back(100.0 * radial);
    const Eigen::Vector3d normal = (std::cos(0.35) * Eigen::Vector3d::UnitZ() + std::sin(0.35) * radial).normalized();
    truth.push_back(normal);
    const Eigen::Vector3d tangent(-std::sin(a), std::cos(a), 0.0);
    t.normals.push_back((Eigen::AngleAxisd(jitter(), tangent) * Eigen::AngleAxisd(jitter(), radial) * normal));
  }
  const auto angle = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / M_PI;
  };
  double before = 0.0;
  for (int i = 0; i < n; ++i) before = std::max(before, angle(t.normals[i], t.normals[(i + 1) % n]));
  smooth_tool_normals(t, 10.0);
  double step = 0.0, error = 0.0;
  for (int i = 0; i < n; ++i) {
    step = std::max(step, angle(t.normals[i], t.normals[(i + 1) % n]));
    error = std::max(error, angle(t.normals[i], truth[static_cast<std::size_t>(i)]));
    EXPECT_NEAR(t.normals[static_cast<std::size_t>(i)].norm(), 1.0, 1e-12);
  }
  const double true_step = angle(truth[0], truth[1]);  // 0.196 degrees: the tilted normal's turn per row
  EXPECT_GT(before, true_step + 0.5);
  EXPECT_LT(step, true_step + 0.1);
  EXPECT_LT(error, 0.3);  // the window's mean of a turning normal is within a hundredth of a degree of the truth
  // An open path's ends average over one side only; a zero window changes nothing.
  Trajectory open{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {30, 0, 0}}, {{0, 0, 1}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}}};
  const Trajectory unchanged = open;
  smooth_tool_normals(open, 0.0);
  EXPECT_EQ(open.normals, unchanged.normals);
  smooth_tool_normals(open, 2.0);
  EXPECT_LT((open.normals[1] - Eigen::Vector3d(0, 1, 1).normalized()).norm(), 1e-12);  // rows 0 and 2 at weight 1/2
  EXPECT_EQ(open.normals[3], Eigen::Vector3d(1, 0, 0));                                // no neighbour within 2 mm
}

TEST(Trajectory, BadTrajectoriesAreRejected) {
  Trajectory t;
  t.points = {{0, 0, 0}};
  t.normals = {{0, 0, 2}};
  EXPECT_THROW(check_trajectory(t, "t.csv"), Error);
  t.normals = {};
  EXPECT_THROW(check_trajectory(t, "t.csv"), Error);
  t.normals = {{0, 0, 1}};
  EXPECT_NO_THROW(check_trajectory(t, "t.csv"));
}

}  // namespace
}  // namespace conform
