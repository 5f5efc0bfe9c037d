// The saddle report's figures: the paper's Table 1 path (R 600, r 150, pose 45 deg, 9 deg steps) drawn whole, the
// closed form along it, the torch at the pose angle from the pipe axis; a long constant-speed path thinned to the
// stated limit with its ends kept.

#include "conform/pipelines/saddle/saddle_report.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/pipelines/saddle/saddle_json.h"
#include "conform/toolpath/saddle/saddle_curve.h"
#include "report_page_checks.h"

namespace conform {
namespace {

SaddleRequest table1() {
  SaddleRequest r;
  r.leg_radius_mm = 600.0;
  r.pipe_radius_mm = 150.0;
  r.right_angle_pose_deg = 45.0;
  r.step_deg = 9.0;
  return r;
}

TEST(SaddleReport, TableOnePathWithItsClosedFormAndTorch) {
  const SaddleJobOptions o = saddle_job_options(table1());
  const SaddleJobResult job = run_saddle(o);
  const SaddleReportFigures f = saddle_report_figures(o, job);
  ASSERT_EQ(f.path.size(), 41u);
  EXPECT_EQ(f.path[10], job.saddle.points[10].position);
  EXPECT_NEAR(f.theta_deg[10], 90.0, 1e-9);
  EXPECT_NEAR(f.z_mm[10], 580.9475, 5e-5);  // Table 1, row 11
  EXPECT_NEAR(f.pose_deg[10], 1.0381 / kPi * 180.0, 5e-3);
  EXPECT_LT(f.max_position_error_mm, 1e-9);
  EXPECT_LT(f.max_pose_error_deg, 1e-9);
  for (std::size_t i = 0; i < f.z_mm.size(); ++i) EXPECT_NEAR(f.z_mm[i], f.closed_z_mm[i], 1e-9);
  // Context meshes: the pipe's wall (distance r from the pipe axis z_P), the cylinder's patch (on the cylinder).
  const SaddleCurve curve(o.saddle.geometry);
  ASSERT_EQ(f.pipe.vertices.size(), 2u * 96u);
  for (const Eigen::Vector3d& v : f.pipe.vertices) EXPECT_NEAR(v.head<2>().norm(), 150.0, 1e-9);
  EXPECT_NEAR(f.pipe.vertices[0].z(), curve.point(0.0).z(), 1e-9);  // its lower edge is the seam
  ASSERT_EQ(f.leg.faces.size(), 2u * 23u * 23u);
  for (const Eigen::Vector3d& v : f.leg.vertices) EXPECT_LT(curve.leg_residual(v), 1e-9);
  // 40 glyphs: the last point is the first again. At theta 0 the pose is 45 deg: between the pipe axis and y_P.
  ASSERT_EQ(f.torch.origins.size(), 40u);
  EXPECT_NEAR((f.torch.directions[0] - Eigen::Vector3d(0.0, std::sqrt(0.5), std::sqrt(0.5))).norm(), 0.0, 1e-12);
  for (std::size_t k = 0; k < f.torch.origins.size(); ++k) {
    const SaddlePoint& p = job.saddle.points[k];
    EXPECT_EQ(f.torch.origins[k], p.position);
    EXPECT_NEAR(std::acos(f.torch.directions[k].dot(Eigen::Vector3d::UnitZ())), p.pose_rad, 1e-12);
  }
}

TEST(SaddleReport, LongPathsAreThinnedToTheLimit) {
  SaddleRequest r = table1();
  r.step_deg.reset();
  r.speed_mm_per_s = 50.0;  // 0.2 mm per 4 ms period: 4,731 points
  r.period_s = 0.004;
  const SaddleJobOptions o = saddle_job_options(r);
  const SaddleJobResult job = run_saddle(o);
  ASSERT_GT(job.saddle.points.size(), kSaddleReportPoints);
  const SaddleReportFigures f = saddle_report_figures(o, job);
  EXPECT_LE(f.path.size(), kSaddleReportPoints + 1);
  EXPECT_EQ(f.path.back(), job.saddle.points.back().position);
  EXPECT_NEAR(f.theta_deg.back(), 360.0, 1e-9);
  EXPECT_EQ(f.step_mm.size(), f.path.size());
  EXPECT_LE(f.torch.origins.size(), kSaddleReportGlyphs + 1);
}

TEST(SaddleReport, PageShowsTheJsonAndDrawsThePath) {
  const SaddleRequest request = table1();
  const SaddleJobOptions o = saddle_job_options(request);
  const SaddleJobResult job = run_saddle(o);
  const html::Page page = saddle_report(request, o, job);
  EXPECT_EQ(page.verdict.level, html::Level::kOk);
  EXPECT_EQ(page.result, saddle_json(request, job));
  EXPECT_GE(test::expect_cells_show_the_json(page), 13u);
  const html::SceneObject* path = test::scene_object(page, "seam path");
  ASSERT_NE(path, nullptr);
  ASSERT_EQ(path->positions.size(), 41u);
  EXPECT_EQ(path->positions[20], job.saddle.points[20].position);
  ASSERT_EQ(page.sections.size(), 1u);
  EXPECT_EQ(page.sections[0].plots.size(), 3u);  // z and pose against the closed form, steps
}

}  // namespace
}  // namespace conform
