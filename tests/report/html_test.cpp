// render_html: the page is self-contained (a Content-Security-Policy that forbids fetches, no URL outside the
// embedded three.js), its JSON is the Result as given, the scene's float32 positions come back to within 1e-4 mm of
// the input 100 m from the origin, tables tie cells to JSON pointers, same page gives the same bytes, and
// write_html leaves nothing behind when it cannot write.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conform/core/error.h"
#include "conform/report/html.h"
#include "page_data.h"
#include "temp_dir.h"

namespace conform::html {
namespace {

using test::decode_base64;
using test::embedded_json;
using test::floats_of;

Page sample_page() {
  Page page;
  page.job = "compare";
  page.inputs = {{"scan.ply", "3 points"}};
  page.options = {{"tolerance_mm", 0.1}, {"units", "mm"}};
  page.date = "2026-11-23 17:00 UTC";
  page.verdict = {Level::kCheck, "within tolerance: 99.0 % <inside>"};
  page.warnings = {"a warning & more"};
  page.result = {{"rms_mm", 0.0123456789}, {"name", "</script><b>"}, {"stats", {{"count", 3}}}};
  Section s;
  s.title = "Statistics";
  s.tables.push_back({"", {"figure", "value"}, {{"RMS (mm)", number(0.0123456789, 4, "/rms_mm")},
                                                  {"points", count(3, "/stats/count")}}});
  s.plots.push_back(histogram_plot({-1.0, 0.0, 0.1, 0.2, 5.0}, 4, -0.5, 0.5, "deviation", "deviation (mm)"));
  page.sections.push_back(s);
  const Eigen::Vector3d far(100000.0, -100000.0, 2500.0);  // 100 m out
  page.scene.add_points("scan", {far, far + Eigen::Vector3d(0.1234, 0, 0), far + Eigen::Vector3d(0, 0.0017, 3.5)},
                        std::vector<Rgb>{{255, 0, 0}, {0, 255, 0}, {0, 0, 255}});
  return page;
}

TEST(ReportHtml, SelfContainedWithPolicyAndNoUrlOutsideThreeJs) {
  const std::string html = render_html(sample_page());
  EXPECT_NE(html.find("content=\"default-src 'none'; script-src 'unsafe-inline'; style-src 'unsafe-inline'; "
                      "img-src data:\""),
            std::string::npos);
  // Cut the two library scripts (three.js's own text holds a namespace URI and links in its comments).
  std::string rest = html;
  const std::size_t lib = rest.find("<script>");
  const std::size_t viewer = rest.rfind("<script>");
  ASSERT_NE(lib, viewer);
  rest.erase(lib, viewer - lib);
  for (const char* forbidden : {"http:", "https:", "src=", "href=", "url(http", "@import", "//cdn"}) {
    EXPECT_EQ(rest.find(forbidden), std::string::npos) << forbidden;
  }
  EXPECT_NE(html.find("OrbitControls"), std::string::npos);
  EXPECT_NE(html.find("REVISION=\"111\""), std::string::npos);  // three.js r111 of Debian's libjs-three
}

TEST(ReportHtml, EmbedsTheResultAndEscapesText) {
  const Page page = sample_page();
  const std::string html = render_html(page);
  EXPECT_EQ(embedded_json(html, "conform-result"), page.result);
  EXPECT_EQ(html.find("</script><b>"), std::string::npos);
  EXPECT_NE(html.find("within tolerance: 99.0 % &lt;inside&gt;"), std::string::npos);
  EXPECT_NE(html.find("class=\"verdict check\""), std::string::npos);
  EXPECT_NE(html.find("a warning &amp; more"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\" data-json=\"/rms_mm\">0.0123</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\" data-json=\"/stats/count\">3</td>"), std::string::npos);
  EXPECT_EQ(render_html(page), html);  // same page, same bytes
}

TEST(ReportHtml, PositionsFarOutComeBackWithinATenthOfAMicrometre) {
  const Page page = sample_page();
  const nlohmann::json scene = embedded_json(render_html(page), "conform-scene");
  ASSERT_TRUE(scene.is_object());
  const Eigen::Vector3d origin(scene["origin"][0], scene["origin"][1], scene["origin"][2]);
  EXPECT_LT((origin - page.scene.origin()).norm(), 1e-6);
  const std::vector<float> local = floats_of(decode_base64(scene["objects"][0]["positions"]));
  const std::vector<Eigen::Vector3d>& input = page.scene.objects()[0].positions;
  ASSERT_EQ(local.size(), 3 * input.size());
  for (std::size_t i = 0; i < input.size(); ++i) {
    const Eigen::Vector3d back = origin + Eigen::Vector3d(local[3 * i], local[3 * i + 1], local[3 * i + 2]);
    EXPECT_LT((back - input[i]).norm(), 1e-4) << i;
  }
  EXPECT_EQ(decode_base64(scene["objects"][0]["colours"]), std::string("\xff\0\0\0\xff\0\0\0\xff", 9));
}

TEST(ReportHtml, HistogramCountsAndEndBars) {
  const Plot p = histogram_plot({-1.0, -0.3, 0.0, 0.1, 0.2, 5.0, NAN}, 4, -0.5, 0.5, "t", "x");
  ASSERT_EQ(p.bars.size(), 4u);
  EXPECT_DOUBLE_EQ(p.bars[0].count, 2.0);  // -1 (beyond) and -0.3
  EXPECT_DOUBLE_EQ(p.bars[1].count, 0.0);
  EXPECT_DOUBLE_EQ(p.bars[2].count, 3.0);  // 0, 0.1 and 0.2 in [0, 0.25)
  EXPECT_DOUBLE_EQ(p.bars[3].count, 1.0);  // 5 (beyond)
  EXPECT_DOUBLE_EQ(p.bars[3].hi, 0.5);
  EXPECT_EQ(p.note, "2 values beyond the axis are counted in the end bars");
}

TEST(ReportHtml, WriteHtmlIsWholeOrNothing) {
  test::TempDir dir;
  write_html(dir.file("r.html"), sample_page());
  EXPECT_EQ(test::read_bytes(dir.file("r.html")), render_html(sample_page()));
  EXPECT_THROW(write_html(dir.file("missing/r.html"), sample_page()), Error);
  EXPECT_EQ(dir.listing(), "r.html\n");
}

}  // namespace
}  // namespace conform::html
