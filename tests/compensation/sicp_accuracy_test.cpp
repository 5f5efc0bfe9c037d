// S-ICP against rigid ICP and the projection model on the generated plate (oval porthole) and nose cone (opening
// with rounded corners), reduced sizes, fixed seeds: the bar (sicp_test_panels.h) and the ordering of the
// three models. Full-size figures: bench/sicp_bench.cpp, docs/sicp.md.

#include <gtest/gtest.h>

#include "sicp_test_panels.h"

namespace conform {
namespace {

TEST(SicpAccuracy, PlateSicpCutsTheRigidErrorByThreeQuarters) {
  const PanelOptions o = test::reduced(PanelShape::kPlate);
  const test::ModelErrors m = test::run_models(o);
  test::expect_sicp_beats_rigid(m, o.noise_mm);
  // The paper's projection model helps on a smooth sag, but less than S-ICP.
  EXPECT_LT(m.projection_error.path_mean_mm, m.rigid_error.path_mean_mm);
  EXPECT_LT(m.sicp_error.path_mean_mm, m.projection_error.path_mean_mm);
  EXPECT_GT(m.sicp.registration.segments.size(), 20u);  // ~1015 mm / 40 mm
  EXPECT_TRUE(m.sicp.registration.joint.usable);
  // Tool normals: the nominal ones rotated by the blended segments and smoothed along the path are within 0.3 degrees
  // on average (a plane fitted to 5 mm of sparse noisy scan beside an edge was 1.3 degrees off); consecutive rows turn
  // by at most a tenth of a degree more than the truth's do.
  EXPECT_LT(m.sicp_error.normal_mean_deg, 0.3);
  EXPECT_LT(m.sicp_error.normal_step_max_deg, m.sicp_error.truth_normal_step_max_deg + 0.1);
}

TEST(SicpAccuracy, NoseConeSicpCutsTheRigidErrorByThreeQuarters) {
  const PanelOptions o = test::reduced(PanelShape::kNoseCone);
  const test::ModelErrors m = test::run_models(o);
  test::expect_sicp_beats_rigid(m, o.noise_mm);
  EXPECT_EQ(m.sicp.registration.segmentation.corners.size(), 4u);  // the opening's four rounded corners
  // Row by row too (the slide along the straight edges included): the same bar.
  EXPECT_LE(m.sicp_error.mean_mm, 0.25 * m.rigid_error.mean_mm);
  EXPECT_LE(m.sicp_error.max_mm, 0.40 * m.rigid_error.max_mm);
  // The joint refinement brings neighbours together on their overlaps.
  EXPECT_LT(m.sicp.registration.joint.max_disagreement_after_mm, m.sicp.registration.joint.max_disagreement_before_mm);
}

}  // namespace
}  // namespace conform
