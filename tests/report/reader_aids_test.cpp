// What a page gives its reader beyond the picture (docs/report.md): per-point values that follow thinning into the
// page (the click readout), callouts at the worst deviations, far apart, a histogram whose axis a few far outliers do
// not stretch (they are counted, and labelled, in the end bars), a colour bar whose labels keep apart and whose title
// wraps inside it, and a reject band drawn as such.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conform/pipelines/common/deviation_view.h"
#include "conform/report/html.h"
#include "page_data.h"

namespace conform::html {
namespace {

using test::decode_base64;
using test::floats_of;

nlohmann::json scene_of(const std::string& html) { return test::embedded_json(html, "conform-scene"); }

// Every number of attribute `name` in the elements of `html` that match `element` (e.g. "<text class=\"label\"").
std::vector<double> attribute_values(const std::string& html, const std::string& element, const std::string& name) {
  std::vector<double> out;
  const std::regex re(element + "[^>]*\\s" + name + "=\"([-0-9.]+)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), re); it != std::sregex_iterator(); ++it) {
    out.push_back(std::stod((*it)[1]));
  }
  return out;
}

TEST(ReportReaderAids, ValuesFollowThinningIntoThePage) {
  Scene::Limits limits;
  limits.max_points = 5;
  Page page;
  page.job = "t";
  page.scene = Scene(limits);
  std::vector<Eigen::Vector3d> points;
  std::vector<double> values;
  for (int i = 0; i < 10; ++i) points.emplace_back(i, 0, 0), values.push_back(0.5 * i);
  SceneObject& o = page.scene.add_points("scan", points, kBlue);
  o.values = values;
  o.value_label = "deviation (mm)";
  const nlohmann::json scene = scene_of(render_html(page));
  ASSERT_TRUE(scene.is_object());
  const nlohmann::json& shown = scene["objects"][0];
  EXPECT_EQ(shown["value_label"], "deviation (mm)");
  const std::vector<float> v = floats_of(decode_base64(shown["values"]));
  ASSERT_EQ(v.size(), 5u);  // every 2nd point, its value with it
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_FLOAT_EQ(v[i], static_cast<float>(values[2 * i])) << i;
  // A value array that does not match the points is refused.
  page.scene.add_points("other", points, kRed).values = {1.0};
  EXPECT_THROW(render_html(page), std::invalid_argument);
}

TEST(ReportReaderAids, WorstDeviationsHaveCalloutsApartAndTheHistogramIgnoresFarOutliers) {
  // 1000 points on a 100 mm line, deviations a smooth +-0.1 mm spread, 2 % of them outliers at +-9 mm.
  std::vector<Eigen::Vector3d> points;
  std::vector<double> d;
  for (int i = 0; i < 1000; ++i) {
    points.emplace_back(0.1 * i, 0.0, 0.0);
    d.push_back(i % 50 == 0 ? (i % 100 == 0 ? 9.0 - 0.001 * i : -9.0 + 0.001 * i) : 0.1 * std::sin(0.37 * i));
  }
  DeviationStatisticsOptions o;
  o.tolerance_mm = 0.05;
  const DeviationStatistics s = deviation_statistics(d, o);
  Mesh reference;
  Page page;
  add_deviation_view(page, points, d, s, reference);
  // Callouts: 5, the first at the largest |deviation| (i = 0: +9 mm), each at least 10 mm (10 % of 100 mm) apart.
  const std::vector<Callout>& callouts = page.scene.callouts();
  ASSERT_EQ(callouts.size(), 5u);
  EXPECT_EQ(callouts[0].label, "1: +9.000 mm");
  EXPECT_EQ(callouts[0].position, points[0]);
  for (std::size_t i = 0; i < callouts.size(); ++i) {
    for (std::size_t j = i + 1; j < callouts.size(); ++j) {
      EXPECT_GE((callouts[i].position - callouts[j].position).norm(), 0.1 * 99.9 - 1e-9);
    }
  }
  // The scan layer carries the deviations for the click readout.
  EXPECT_EQ(page.scene.objects()[0].values, d);
  // The histogram spans about the +-0.1 mm spread (+-0.2 with its fences; an axis to +-9 would put it in one or two
  // bars): about half of its 60 bars hold points, the 20 outliers are in the end bars, counted and labelled.
  ASSERT_EQ(page.sections.size(), 1u);
  ASSERT_EQ(page.sections[0].plots.size(), 1u);
  const Plot& h = page.sections[0].plots[0];
  EXPECT_LT(h.bars.back().hi, 0.25);
  EXPECT_GT(h.bars.front().lo, -0.25);
  int filled = 0;
  for (const Bar& b : h.bars) filled += b.count > 0;
  EXPECT_GT(filled, 25);
  EXPECT_EQ(h.below, 10u);
  EXPECT_EQ(h.above, 10u);
  const std::string html = render_html(page);
  EXPECT_NE(html.find("10 below "), std::string::npos);
  EXPECT_NE(html.find("10 above "), std::string::npos);
  EXPECT_EQ(attribute_values(html, "<rect class=\"bar overflow\"", "x").size(), 2u);
  // The worst points are listed in a table too.
  ASSERT_EQ(page.sections[0].tables.size(), 2u);
  EXPECT_EQ(page.sections[0].tables[1].rows.size(), 5u);
}

TEST(ReportReaderAids, ColourBarLabelsKeepApartAndTheTitleWraps) {
  Page page;
  page.job = "t";
  page.scene.add_points("p", {{0, 0, 0}, {1, 1, 1}}, kBlue);
  // A band of +-0.01 on a +-3 scale: its two labels would sit 0.7 px apart.
  ColourBar bar = make_colour_bar("depth below the reference surface (mm)", "grey above the threshold, yellow to dark red",
                                  -3.0, 3.0, [](double) { return kBlue; });
  bar.band = std::make_pair(-0.01, 0.01);
  page.scene.set_colour_bar(bar);
  const std::string html = render_html(page);
  std::vector<double> y = attribute_values(html, "<text class=\"label\"", "y");
  ASSERT_EQ(y.size(), 4u);
  for (std::size_t i = 1; i < y.size(); ++i) EXPECT_GE(y[i] - y[i - 1], 13.0 - 1e-9) << i;
  // The title and the caption on lines of at most 22 and 28 characters (the bar is 150 px wide).
  const std::regex title("<text x=\"4\" y=\"[0-9.]+\" class=\"title\">([^<]*)</text>");
  int lines = 0;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), title); it != std::sregex_iterator(); ++it, ++lines) {
    EXPECT_LE((*it)[1].length(), 22u) << (*it)[1];
  }
  EXPECT_EQ(lines, 2);
  EXPECT_EQ(attribute_values(html, "<text class=\"caption\"", "x").size(), 2u);
}

TEST(ReportReaderAids, RejectBandIsDrawnAsSuch) {
  Page page;
  page.job = "t";
  Plot p;
  p.series.push_back({"c", {1, 2, 3}, {0.9, 1.0, 0.95}, kPurple, false});
  p.y_band = Band{0.0, 0.5, "untrusted below this", true};
  page.sections.push_back({"s", {}, {}, {p}});
  const std::string html = render_html(page);
  EXPECT_NE(html.find("<rect class=\"band reject\""), std::string::npos);
  EXPECT_NE(html.find("svg .band.reject{fill:#d62728"), std::string::npos);
}

}  // namespace
}  // namespace conform::html
