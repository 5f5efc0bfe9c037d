// The profile report's figures on generated profiles (datasets/profile.h, seeded): the mapped outlines are the
// Result's, the nominal ones lie on the straight profile, and a feature's displacement is the generator's bow there.

#include "conform/pipelines/profile/profile_report.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/pipelines/generate/generate_profile.h"
#include "report_page_checks.h"
#include "temp_dir.h"

namespace conform {
namespace {

// A 2.4 m profile with three holes (Ty = L/6, L/2, 5L/6 at Tx = 100 mm) and a marking line, bowed in plane by `bow`.
ProfileJobResult run(const test::TempDir& dir, double bow) {
  GenerateProfileOptions g;
  g.scan.deformation.length_mm = 2400.0;
  g.scan.deformation.bow_in_plane_mm = bow;
  g.scan.holes = 3;
  g.scan.marking_line = true;
  g.scan.seed = 3;
  g.out_path = dir.file("p.csv");
  const GenerateProfileResult files = run_generate_profile(g);
  ProfileJobOptions o;
  o.edge_path = files.edge_path;
  o.features_path = files.features_path;
  o.keep_geometry = true;
  return run_profile(o);
}

TEST(ProfileReport, MappedOutlinesAreTheResultsAndNominalOnesLieOnTheStraightProfile) {
  const test::TempDir dir;
  const ProfileJobResult job = run(dir, 10.0);
  ASSERT_TRUE(job.compensation.ok);
  const ProfileReportFigures f = profile_report_figures(job);
  EXPECT_EQ(f.edge.size(), job.edge_points);
  ASSERT_EQ(f.edge_curve.size(), kProfileReportCurvePoints);
  EXPECT_NEAR((f.edge_curve.back() - f.edge_curve.front()).norm(), 2400.0, 1.0);  // bow 10 mm: chord ~ length
  ASSERT_EQ(f.features.size(), job.compensation.features.size());
  ASSERT_EQ(f.features.size(), 4u);  // H1..H3, M1
  for (std::size_t k = 0; k < f.features.size(); ++k) {
    const ProfileFeatureResult& r = job.compensation.features[k];
    const ProfileFeatureFigure& g = f.features[k];
    EXPECT_EQ(g.id, r.id);
    EXPECT_EQ(g.mapped, r.mapped);
    ASSERT_EQ(g.nominal.size(), r.designed.size());
    for (std::size_t i = 0; i < g.nominal.size(); ++i) {
      // (Tx, Ty) back from the straight frame.
      const Eigen::Vector3d d = g.nominal[i] - f.straight.origin;
      EXPECT_NEAR(d.dot(f.straight.along), r.designed[i].y(), 1e-9);
      EXPECT_NEAR(d.dot(f.straight.across), r.designed[i].x(), 1e-9);
    }
    EXPECT_NEAR(g.displacement_mm, (g.mapped_at - g.nominal_at).norm(), 1e-12);
    EXPECT_GE(g.max_displacement_mm, g.displacement_mm);
  }
  // The middle hole (Ty = L/2, where the bow's slope is 0) is displaced by the bow, 10 mm, across the web.
  const ProfileFeatureFigure& middle = f.features[1];
  EXPECT_EQ(middle.type, "circle");
  EXPECT_NEAR(middle.designed.y(), 1200.0, 1e-9);
  EXPECT_NEAR(middle.displacement_mm, 10.0, 0.5);
}

TEST(ProfileReport, AStraightProfileDisplacesNothing) {
  const test::TempDir dir;
  const ProfileReportFigures f = profile_report_figures(run(dir, 0.0));
  ASSERT_EQ(f.features.size(), 4u);
  for (const ProfileFeatureFigure& g : f.features) EXPECT_LT(g.max_displacement_mm, 0.5) << g.id;  // noise 0.1 mm
}

TEST(ProfileReport, PageDrawsTheFeaturesAndShowsItsJson) {
  const test::TempDir dir;
  const ProfileJobResult job = run(dir, 10.0);
  ProfileJobOptions o;
  o.edge_path = "p.csv";
  o.features_path = "p.features.csv";
  const html::Page page = profile_report(o, job);
  // One edge: the twist it cannot see is a warning per feature, so the page asks for a check.
  EXPECT_EQ(page.verdict.level, html::Level::kCheck);
  ASSERT_FALSE(page.warnings.empty());
  EXPECT_NE(page.warnings.back().find("twist is not observed"), std::string::npos);
  EXPECT_GT(test::expect_cells_show_the_json(page), 20u);
  const html::SceneObject* mapped = test::scene_object(page, "features, mapped (deformed profile)");
  ASSERT_NE(mapped, nullptr);
  std::size_t segments = 0;
  for (const ProfileFeatureResult& f : job.compensation.features) segments += f.mapped.size() - 1;
  EXPECT_EQ(mapped->positions.size(), 2 * segments);  // every outline as segment pairs
  EXPECT_EQ(mapped->positions[1], job.compensation.features[0].mapped[1]);
  const html::SceneObject* edge = test::scene_object(page, "edge points");
  ASSERT_NE(edge, nullptr);
  EXPECT_EQ(edge->positions.size(), job.edge_points);
  // The plan view: every feature's outline, nominal and mapped, in (along the chord, across) of the straight frame,
  // one line per feature (NaN between them).
  ASSERT_FALSE(page.sections.empty());
  EXPECT_EQ(page.sections.front().title, "Plan view");
  ASSERT_EQ(page.sections.front().plots.size(), 1u);
  const html::Plot& plan = page.sections.front().plots[0];
  const ProfileReportFigures f = profile_report_figures(job);
  const html::Series* plan_mapped = nullptr;
  for (const html::Series& s : plan.series) plan_mapped = s.name == "features, mapped" ? &s : plan_mapped;
  ASSERT_NE(plan_mapped, nullptr);
  std::size_t at = 0;
  for (const ProfileFeatureFigure& g : f.features) {
    for (const Eigen::Vector3d& q : g.mapped) {
      ASSERT_LT(at, plan_mapped->x.size());
      EXPECT_NEAR(plan_mapped->x[at], (q - f.straight.origin).dot(f.straight.along), 1e-9);
      EXPECT_NEAR(plan_mapped->y[at], (q - f.straight.origin).dot(f.straight.across), 1e-9);
      ++at;
    }
    ASSERT_LT(at, plan_mapped->x.size());
    EXPECT_TRUE(std::isnan(plan_mapped->x[at++])) << g.id;
  }
  EXPECT_EQ(at, plan_mapped->x.size());
}

}  // namespace
}  // namespace conform
