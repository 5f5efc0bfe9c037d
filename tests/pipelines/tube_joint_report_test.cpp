// The tube-joint report's figures on a generated joint (datasets/tube_joint.h; pitch 60 deg, offset 30 mm, noise
// 0.2 mm, seeded): the leg drawn in S is the leg mesh posed by T_S_L, the path is the Result's seam, each tool glyph
// runs from the tool's position to its seam point over the standoff (Eq. 9 and 11), and the angle plots are the
// Result's dihedral and groove angles.

#include "conform/pipelines/tube_joint/tube_joint_report.h"

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/pipelines/generate/generate_tube_joint.h"
#include "conform/pipelines/generate/generate_tube_joint_json.h"
#include "conform/pipelines/tube_joint/tube_joint_json.h"
#include "report_page_checks.h"
#include "temp_dir.h"

namespace conform {
namespace {

TEST(TubeJointReport, MeshesPathAndToolGlyphs) {
  const test::TempDir dir;
  GenerateTubeJointRequest g;
  g.job.leg_path = dir.file("leg.ply");
  g.job.stub_path = dir.file("stub.ply");
  g.job.truth_path = dir.file("truth.csv");
  g.job.joint.leg.radius_mm = 300.0;
  g.job.stub_outer_radius_mm = 160.0;
  g.job.wall_mm = 10.0;
  g.job.spec.offset_mm = 30.0;
  g.job.joint.truth_points = 360;
  g.pitch_deg = 60.0;
  g.edge_mm = 10.0;
  g.noise_mm = 0.2;
  const GenerateTubeJointResult generated = run_generate_tube_joint(generate_tube_joint_options(g));

  TubeJointRequest request;
  request.job.leg_path = g.job.leg_path;
  request.job.stub_path = g.job.stub_path;
  request.job.spec.offset_mm = 30.0;
  request.job.spec.protrusion_mm = generated.spec.protrusion_mm;
  request.job.keep_geometry = true;
  request.pitch_deg = 60.0;
  request.protrusion_given = true;
  request.step_deg = 2.0;
  request.groove_deg = std::array<double, 4>{30.0, 45.0, 20.0, 45.0};
  const TubeJointJobOptions options = tube_joint_job_options(request);
  const TubeJointJobResult job = run_tube_joint(options);
  ASSERT_TRUE(job.solution.ok) << job.solution.termination;
  const TubeJointReportFigures f =
      tube_joint_report_figures(job, options.solve.tools.cut_standoff_mm, options.solve.tools.weld_standoff_mm);

  ASSERT_EQ(f.leg_S.vertices.size(), job.leg_L.vertices.size());
  EXPECT_EQ(f.leg_S.faces, job.leg_L.faces);
  EXPECT_EQ(job.stub_S.faces.size(), job.stub_faces);
  for (std::size_t i = 0; i < f.leg_S.vertices.size(); i += 97) {
    EXPECT_NEAR((f.leg_S.vertices[i] - job.T_S_L * job.leg_L.vertices[i]).norm(), 0.0, 1e-9);
  }
  const std::vector<PathFrame>& frames = job.solution.frames;
  ASSERT_EQ(frames.size(), 180u);  // 2 deg steps
  ASSERT_EQ(f.path.size(), frames.size() + 1);
  EXPECT_EQ(f.path.front(), f.path.back());
  EXPECT_EQ(f.path[7], frames[7].point);
  // Every glyph ends on its seam point: p_c + s_c d_c = p (Eq. 9), p_w + s_w d_w = p (Eq. 11).
  const std::vector<std::size_t> rows = spread_indices(frames.size(), kTubeJointReportGlyphs);
  ASSERT_EQ(f.cut.origins.size(), rows.size());
  ASSERT_EQ(f.weld.origins.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const Eigen::Vector3d& p = frames[rows[k]].point;
    EXPECT_NEAR((f.cut.origins[k] + f.cut_standoff_mm * f.cut.directions[k] - p).norm(), 0.0, 1e-9);
    EXPECT_NEAR((f.weld.origins[k] + f.weld_standoff_mm * f.weld.directions[k] - p).norm(), 0.0, 1e-9);
  }
  // Along the azimuth: the groove table's quarters (30 deg at the toe, 20 at the heel), the dihedral of the Result.
  ASSERT_EQ(f.azimuth_deg.size(), frames.size());
  EXPECT_NEAR(f.azimuth_deg[0], 0.0, 1e-9);
  EXPECT_NEAR(f.groove_deg[0], 30.0, 1e-9);
  EXPECT_NEAR(f.groove_deg[90], 20.0, 1e-9);  // phi = 180 deg
  EXPECT_NEAR(f.weld_deg[45], 45.0, 1e-9);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_NEAR(f.dihedral_deg[i], job.solution.tools.psi_rad[i] / kPi * 180.0, 1e-9);
  }
  EXPECT_EQ(tube_joint_json(job)["points"].get<std::size_t>(), frames.size());

  // The page: both meshes, the seam, the tools; every tied number is the JSON's.
  const html::Page page = tube_joint_report(options, job);
  EXPECT_EQ(page.verdict.level, html::Level::kCheck);  // walls not checked
  EXPECT_GT(test::expect_cells_show_the_json(page), 14u);
  const html::SceneObject* leg = test::scene_object(page, "leg (outer surface)");
  ASSERT_NE(leg, nullptr);
  EXPECT_EQ(leg->triangles.size(), job.leg_faces);
  const html::SceneObject* seam = test::scene_object(page, "seam path");
  ASSERT_NE(seam, nullptr);
  EXPECT_EQ(seam->positions, f.path);
  const html::SceneObject* cut = test::scene_object(page, "cutting tool");
  ASSERT_NE(cut, nullptr);
  EXPECT_EQ(cut->length_mm, 10.0);  // the standoff
  EXPECT_EQ(page.options["groove_deg"][0].get<double>(), 30.0);
}

}  // namespace
}  // namespace conform
