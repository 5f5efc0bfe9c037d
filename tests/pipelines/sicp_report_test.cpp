// The sicp report's figures on a generated plate (datasets/panel.h, seeded): the compensated path drawn is the
// Result's trajectory, the nominal path and the contour are the files read, the glyphs are compensated rows with
// their tool normals, and the per-row and per-segment series are the checks' figures.

#include "conform/pipelines/sicp/sicp_report.h"

#include <gtest/gtest.h>

#include "conform/pipelines/generate/generate_panel.h"
#include "conform/pipelines/sicp/sicp_json.h"
#include "report_page_checks.h"
#include "temp_dir.h"

namespace conform {
namespace {

struct SharedRun {
  test::TempDir dir;
  SicpJobResult result;
  SharedRun() {
    GeneratePanelOptions g;
    g.panel.scan_points = 8000;
    g.panel.contour_spacing_mm = 2.0;
    g.panel.surface_edge_mm = 4.0;
    g.out_path = dir.file("p.ply");
    const GeneratePanelResult files = run_generate_panel(g);
    SicpJobOptions o;
    o.contour_path = files.files.contour;
    o.scan_path = files.files.scan;
    o.trajectory_path = files.files.trajectory;
    o.surface_path = files.files.nominal;
    o.keep_geometry = true;
    result = run_sicp(o);
  }
};

const SharedRun& shared_run() {
  static const SharedRun run;
  return run;
}

TEST(SicpReport, FiguresAreTheResultsPathsAndRows) {
  const SicpJobResult& r = shared_run().result;
  ASSERT_TRUE(r.compensation.trusted) << r.compensation.check.reason;
  const SicpReportFigures f = sicp_report_figures(r, SicpCheckOptions{}.min_confidence);
  ASSERT_EQ(f.compensated.size(), r.trajectory_rows);
  for (std::size_t i = 0; i < f.compensated.size(); ++i) {
    EXPECT_EQ(f.compensated[i], r.compensation.trajectory.points[i]);
  }
  EXPECT_EQ(f.nominal.size(), r.trajectory_rows);
  EXPECT_EQ(f.contour.size(), r.contour_points + 1);  // closed: back to its first point
  EXPECT_EQ(f.contour.front(), f.contour.back());
  // The correction moves each row by less than the generator's deformation (sag 4 mm, bend, twist 1.5 mm).
  for (std::size_t i = 0; i < f.nominal.size(); ++i) EXPECT_LT((f.compensated[i] - f.nominal[i]).norm(), 10.0);
  // Glyphs: compensated rows with their unit tool normals, at most the stated limit (+ the last row).
  ASSERT_GT(f.normals.origins.size(), 100u);
  ASSERT_LE(f.normals.origins.size(), kSicpReportGlyphs + 1);
  const std::vector<std::size_t> rows = spread_indices(r.trajectory_rows, kSicpReportGlyphs);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(f.normals.origins[k], r.compensation.trajectory.points[rows[k]]);
    EXPECT_NEAR(f.normals.directions[k].norm(), 1.0, 1e-9);
  }
  // Per row: the --out-rows figures; a trusted run has no untrusted row.
  ASSERT_EQ(f.row.size(), r.trajectory_rows);
  EXPECT_EQ(f.row.front(), 1.0);
  for (std::size_t i = 0; i < f.row.size(); ++i) {
    EXPECT_EQ(f.across_mm[i], r.compensation.check.rows[i].across_mm);
    EXPECT_EQ(f.axis_mm[i], r.compensation.check.rows[i].axis_mm);
    EXPECT_EQ(f.along_mm[i], r.compensation.check.rows[i].along_mm);
    EXPECT_EQ(f.confidence[i], r.compensation.check.rows[i].confidence);
  }
  EXPECT_TRUE(f.untrusted.empty());
  // Per segment: the JSON's segments, their residuals.
  const nlohmann::json j = sicp_json(r);
  ASSERT_EQ(f.segment.size(), j["segments"].size());
  for (std::size_t k = 0; k < f.segment.size(); ++k) {
    EXPECT_EQ(f.segment_rms_mm[k], j["segments"][k]["rms_mm"].get<double>());
    EXPECT_LT(f.segment_rms_mm[k], 0.2);  // noise 0.05 mm
  }
}

TEST(SicpReport, RowsBelowTheThresholdAreMarked) {
  const SicpJobResult& r = shared_run().result;
  const SicpReportFigures f = sicp_report_figures(r, 1.01);  // no row reaches it
  EXPECT_EQ(f.untrusted.size(), r.trajectory_rows);
}

TEST(SicpReport, PageDrawsTheResultAndShowsItsJson) {
  const SharedRun& run = shared_run();
  SicpJobOptions o;
  o.contour_path = "p.contour.csv";
  o.scan_path = "p.ply";
  o.trajectory_path = "p.trajectory.csv";
  const html::Page page = sicp_report(o, run.result);
  EXPECT_EQ(page.job, "sicp");
  EXPECT_EQ(page.verdict.level, html::Level::kOk);
  EXPECT_EQ(page.result, sicp_json(run.result));
  EXPECT_GT(test::expect_cells_show_the_json(page), 26u * 6u);  // the summary and every segment's row
  const html::SceneObject* scan = test::scene_object(page, "scan");
  ASSERT_NE(scan, nullptr);
  EXPECT_EQ(scan->original_count, run.result.scan_points);
  const html::SceneObject* path = test::scene_object(page, "compensated trajectory");
  ASSERT_NE(path, nullptr);
  EXPECT_EQ(path->positions, run.result.compensation.trajectory.points);
  const html::SceneObject* normals = test::scene_object(page, "tool normals");
  ASSERT_NE(normals, nullptr);
  EXPECT_EQ(normals->kind, html::ObjectKind::kArrows);
  EXPECT_EQ(normals->positions.size(), spread_indices(run.result.trajectory_rows, kSicpReportGlyphs).size());
  // The confidence plot's zone below --min-confidence is a reject band (red), the residual's a green one.
  ASSERT_EQ(page.sections.back().plots.size(), 3u);
  ASSERT_TRUE(page.sections.back().plots[1].y_band.has_value());
  EXPECT_TRUE(page.sections.back().plots[1].y_band->reject);
  EXPECT_DOUBLE_EQ(page.sections.back().plots[1].y_band->hi, o.compensation.checks.min_confidence);
  EXPECT_FALSE(page.sections.back().plots[2].y_band->reject);
  // An untrusted run says why in the verdict.
  SicpJobResult failed = run.result;
  failed.compensation.trusted = false;
  failed.compensation.check.reason = "3 rows without edge scan";
  const html::Page bad = sicp_report(o, failed);
  EXPECT_EQ(bad.verdict.level, html::Level::kFail);
  EXPECT_NE(bad.verdict.text.find("3 rows without edge scan"), std::string::npos);
}

}  // namespace
}  // namespace conform
