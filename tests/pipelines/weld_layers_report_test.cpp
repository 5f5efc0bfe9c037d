// The weld-layers report's figures on a generated blade (datasets/eroded.h: 60 x 40 mm on a 2 mm grid, one crater of
// radius 10 mm and depth 1.5 mm, seeded): the surface is the eroded grid with its depth, thinned to a stated node
// limit; the rims and each layer's paths are the Result's.

#include "conform/pipelines/weld_layers/weld_layers_report.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "conform/pipelines/generate/generate_eroded.h"
#include "report_page_checks.h"
#include "temp_dir.h"

namespace conform {
namespace {

struct SharedRun {
  test::TempDir dir;
  WeldLayersJobResult job;
  SharedRun() {
    GenerateErodedOptions g;
    g.eroded.rows = 21;
    g.eroded.cols = 31;
    g.eroded.length_mm = 60.0;
    g.eroded.width_mm = 40.0;
    g.eroded.craters = {Crater{0.0, 0.0, 10.0, 1.5}};
    g.eroded.noise_mm = 0.005;
    g.out_path = dir.file("blade.csv");
    const GenerateErodedResult files = run_generate_eroded(g);
    WeldLayersJobOptions o;
    o.eroded_path = files.eroded_path;
    o.reference_path = files.reference_path;
    o.weld.bead_spacing_mm = 2.0;
    o.weld.layer_height_mm = 0.8;
    o.weld.chord_error_mm = 0.05;
    o.weld.torch_distance_mm = 10.0;
    o.keep_geometry = true;
    job = run_weld_layers(o);
  }
};

const SharedRun& shared_run() {
  static const SharedRun run;
  return run;
}

TEST(WeldLayersReport, SurfaceRimsAndLayersAreTheResults) {
  const WeldLayersJobResult& job = shared_run().job;
  const WeldLayerResult& w = job.weld;
  ASSERT_TRUE(w.ok) << w.termination;
  const WeldLayersReportFigures f = weld_layers_report_figures(job);
  EXPECT_EQ(f.stride, 1);
  ASSERT_EQ(f.surface.vertices.size(), 21u * 31u);
  EXPECT_EQ(f.surface.faces.size(), 2u * 20u * 30u);
  EXPECT_EQ(f.surface.vertices[40], job.eroded.points[40]);
  // The deepest node is the crater's bottom: 1.5 mm (noise 0.005 mm).
  EXPECT_NEAR(*std::max_element(f.depth_mm.begin(), f.depth_mm.end()), 1.5, 0.05);
  EXPECT_NEAR(*std::max_element(f.depth_mm.begin(), f.depth_mm.end()), w.max_depth_mm, 1e-12);
  ASSERT_EQ(f.rims.size(), w.rims.size());
  ASSERT_EQ(f.rims.size(), 1u);
  EXPECT_EQ(f.rims[0].size(), w.rims[0].points.size() + (w.rims[0].closed ? 1 : 0));
  ASSERT_EQ(f.layers.size(), static_cast<std::size_t>(w.layers));
  std::size_t paths = 0;
  double length = 0.0;
  for (std::size_t k = 0; k < f.layers.size(); ++k) {
    EXPECT_EQ(f.layers[k].layer, static_cast<int>(k + 1));
    EXPECT_EQ(f.layers[k].paths.size(), static_cast<std::size_t>(w.paths_per_layer[k]));
    EXPECT_EQ(f.layers[k].coverage_pct, w.coverage_pct[k]);
    paths += f.layers[k].paths.size();
    length += f.layers[k].length_mm;
  }
  EXPECT_EQ(paths, w.paths.size());
  EXPECT_NEAR(length, w.total_length_mm, 1e-9);
}

TEST(WeldLayersReport, BigGridsAreThinnedToTheLimitKeepingTheirBorder) {
  const WeldLayersJobResult& job = shared_run().job;
  const WeldLayersReportFigures f = weld_layers_report_figures(job, 100);
  EXPECT_EQ(f.stride, 3);                          // ceil(sqrt(651 / 100))
  ASSERT_EQ(f.surface.vertices.size(), 8u * 11u);  // rows 0, 3, ..., 18, 20; columns 0, 3, ..., 30
  EXPECT_EQ(f.surface.vertices.back(), job.eroded.at(20, 30));
  EXPECT_EQ(f.surface.faces.size(), 2u * 7u * 10u);
}

TEST(WeldLayersReport, PageDrawsEveryLayerAndShowsItsJson) {
  const SharedRun& run = shared_run();
  WeldLayersJobOptions o;
  o.eroded_path = "blade.csv";
  o.weld.min_coverage_pct = 90.0;
  const html::Page page = weld_layers_report(o, run.job);
  EXPECT_EQ(page.result["paths"].get<std::size_t>(), run.job.weld.paths.size());
  EXPECT_GT(test::expect_cells_show_the_json(page), 15u);
  const html::SceneObject* surface = test::scene_object(page, "eroded surface");
  ASSERT_NE(surface, nullptr);
  EXPECT_EQ(surface->colours.size(), surface->positions.size());
  // A click on the surface reads its depth; each crater's deepest point has a callout.
  EXPECT_EQ(surface->values.size(), surface->positions.size());
  EXPECT_EQ(surface->value_label, "depth (mm)");
  const std::vector<DamageRegion>& craters = run.job.weld.damage.regions;
  ASSERT_EQ(page.scene.callouts().size(), craters.size());
  for (std::size_t k = 0; k < craters.size(); ++k) {
    EXPECT_EQ(page.scene.callouts()[k].position, craters[k].deepest);
    EXPECT_EQ(page.scene.callouts()[k].label.rfind("crater " + std::to_string(craters[k].id) + ": ", 0), 0u);
  }
  ASSERT_TRUE(page.scene.colour_bar().has_value());
  for (int k = 1; k <= run.job.weld.layers; ++k) {
    const html::SceneObject* layer = test::scene_object(page, "layer " + std::to_string(k));
    ASSERT_NE(layer, nullptr);
    EXPECT_TRUE(layer->pieces);
  }
  // Depth colours: grey above the threshold, the ramp's ends at the threshold and the deepest point.
  EXPECT_EQ(depth_colour(0.0, 0.05, 1.5), (html::Rgb{215, 215, 215}));
  EXPECT_EQ(depth_colour(1.5, 0.05, 1.5), (html::Rgb{150, 0, 0}));
  EXPECT_EQ(depth_colour(9.0, 0.05, 1.5), (html::Rgb{150, 0, 0}));
  EXPECT_EQ(depth_colour(0.050001, 0.05, 1.5)[1], 220);
}

}  // namespace
}  // namespace conform
