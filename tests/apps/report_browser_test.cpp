// The HTML reports (--report, docs/report.md) rendered in a real browser: headless Chromium with software WebGL
// (SwiftShader) opens each report from disk, and the test asserts from its screenshot and its DOM that
//  1. the 3D view drew: the canvas was cleared to the view's background and has geometry on it,
//  2. compare's and align's views show the deviation map's colours (its green, and the red of the bump),
//  3. the page asked for nothing over the network: Chromium's net log holds no http(s)/ws request from the page
//     (the page's requests carry its file:// origin, "null"; Chromium's own background requests "not an origin";
//     NetworkCheckSeesAFetch shows that a page which does fetch is caught),
//  4. the numbers in the page's tables are the job's --json output (each cell tied to a JSON pointer, equal to
//     the shown precision), and the JSON embedded in the page is that output,
//  5. what a reader sees, measured in the page by a probe script the test appends (report_reader_probe.h): framing,
//     swatches, the colour bar's labels, the histogram's bars, the click readout, callouts, reject bands.
// One line in kReports adds a job. Skipped when Chromium is not installed (CI installs it: scripts/setup.sh).
// The suite's name holds "Matrix": CI's sanitizer stage skips it (the browser is not instrumented; the release
// stage runs it). CONFORM_UPDATE_DOCS_IMAGES=1 writes each screenshot to docs/images/report_<job>.png.

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "conform/report/html.h"
#include "page_data.h"
#include "report_reader_probe.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

struct ReportCase {
  std::string job;
  std::vector<std::vector<std::string>> setup;  // conform commands that make the inputs; {dir}: the scratch folder
  std::vector<std::string> command;             // the job; {report}: the page to write; must print --json
  int exit_code = 0;
  bool deviation_colours = false;  // the view shows the deviation map (its green and red)
  std::size_t min_tied_cells = 5;  // table cells tied to the JSON, at least
  test::ReaderAids reader;         // what the probe must find (report_reader_probe.h)
};

// gtest prints a case by its job (the ctest names stay readable and the same from run to run).
void PrintTo(const ReportCase& c, std::ostream* os) { *os << c.job; }

const std::vector<std::string> kPatch = {"generate", "tube", "--quiet", "--radius", "100", "--length", "80",
                                         "--arc-deg", "60"};

std::vector<std::string> with(std::vector<std::string> base, const std::vector<std::string>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

const ReportCase kReports[] = {
    {"compare",
     {with(kPatch, {"--edge", "0.8", "--out", "{dir}/nominal.ply"}),
      with(kPatch, {"--edge", "2", "--bump", "0,0,1.5,15", "--out", "{dir}/scan.ply"})},
     {"compare", "--scan", "{dir}/scan.ply", "--reference", "{dir}/nominal.ply", "--tolerance", "0.5", "--report",
      "{report}", "--json"},
     0, true, 12, {"deviation (mm)", 3, 15}},
    {"align",
     {with(kPatch, {"--edge", "2.5", "--out", "{dir}/ref.ply"}),
      with(kPatch, {"--edge", "2", "--bump", "0,0,1.5,15", "--noise", "0.02", "--out", "{dir}/scan.ply"})},
     {"align", "--scan", "{dir}/scan.ply", "--reference", "{dir}/ref.ply", "--report", "{report}", "--json"}, 0, true,
     20, {"deviation (mm)", 3, 15}},
    {"fit_cylinder",
     {{"generate", "tube", "--quiet", "--radius", "150", "--arc-deg", "120", "--length", "150", "--edge", "3",
       "--noise", "0.05", "--outliers", "0.02", "--out", "{dir}/tube.ply"}},
     {"fit-cylinder", "--input", "{dir}/tube.ply", "--quiet", "--report", "{report}", "--json"}, 0, false, 15,
     {"residual (mm)", 5, 25}},
    {"sicp",
     {{"generate", "plate", "--out", "{dir}/p.ply", "--scan-points", "8000", "--contour-spacing", "2",
       "--surface-edge", "4", "--quiet"}},
     {"sicp", "--contour", "{dir}/p.contour.csv", "--scan", "{dir}/p.ply", "--trajectory", "{dir}/p.trajectory.csv",
      "--surface", "{dir}/p.nominal.ply", "--truth", "{dir}/p.truth.csv", "--quiet", "--report", "{report}", "--json"},
     0, false, 100, {"", 0, 0}},
    {"profile",
     {{"generate", "profile", "--out", "{dir}/p.csv", "--length", "3000", "--bow", "40", "--holes", "3",
       "--marking-line"}},
     {"profile", "--edge", "{dir}/p.csv", "--features", "{dir}/p.features.csv", "--report", "{report}", "--json"}, 0,
     false, 20, {"", 0, 0}},
    {"tube_joint",
     {{"generate", "tube-joint", "--out-leg", "{dir}/leg.ply", "--out-stub", "{dir}/stub.ply", "--out-truth",
       "{dir}/truth.csv", "--leg-radius", "300", "--stub-radius", "160", "--wall", "10", "--edge", "10",
       "--pitch-deg", "60", "--offset", "30", "--protrusion", "540", "--noise", "0.2"}},
     {"tube-joint", "--leg", "{dir}/leg.ply", "--stub", "{dir}/stub.ply", "--pitch-deg", "60", "--offset", "30",
      "--protrusion", "540", "--step-deg", "2", "--groove-deg", "30,45,20,45", "--quiet", "--report", "{report}",
      "--json"},
     0, false, 14, {"", 0, 0}},
    {"saddle",
     {},
     {"saddle", "--R", "600", "--r", "150", "--pitch-deg", "60", "--offset", "100", "--start-pose-deg", "45",
      "--speed", "500", "--period", "0.004", "--report", "{report}", "--json"},
     0, false, 13, {"", 0, 0}},
    {"weld_layers",
     {{"generate", "eroded", "--out", "{dir}/blade.csv", "--crater", "0,0,15,2", "--crater", "35,10,8,1", "--crater",
       "55,-30,10,1.5"}},
     {"weld-layers", "--eroded", "{dir}/blade.csv", "--reference", "{dir}/blade.reference.csv", "--bead-spacing", "3",
      "--layer-height", "1", "--chord-error", "0.05", "--torch-distance", "2", "--report", "{report}", "--json"},
     0, false, 15, {"depth (mm)", 3, 0}},
};

std::string expand(const std::string& arg, const test::TempDir& dir) {
  std::string out = std::regex_replace(arg, std::regex("\\{dir\\}"), dir.path());
  return std::regex_replace(out, std::regex("\\{report\\}"), dir.file("report.html"));
}

std::string chromium_path() {
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser", "/usr/bin/google-chrome"}) {
    if (std::filesystem::exists(p)) return p;
  }
  return "";
}

struct Rendered {
  test::RunResult run;
  std::string dom;
  cv::Mat screenshot;                      // BGR
  std::vector<std::string> page_requests;  // network URLs the page asked for
  nlohmann::json probe;                    // kProbe's measurements (null without the probe)
};

// The page's network requests in Chromium's net log (see the file comment).
std::vector<std::string> page_requests(const std::string& net_log_path) {
  std::string text = test::read_bytes(net_log_path);
  nlohmann::json log = nlohmann::json::parse(text, nullptr, false);
  if (log.is_discarded()) log = nlohmann::json::parse(text + "]}", nullptr, false);  // cut short at exit
  std::vector<std::string> urls;
  if (log.is_discarded()) return {"(net log unreadable: " + net_log_path + ")"};
  const auto& events = log["events"];
  for (const auto& e : events) {
    if (!e.contains("params") || !e["params"].is_object()) continue;
    const auto& p = e["params"];
    if (!p.contains("url") || !p.contains("initiator")) continue;
    const std::string url = p["url"].get<std::string>(), initiator = p["initiator"].get<std::string>();
    const bool network = url.rfind("http:", 0) == 0 || url.rfind("https:", 0) == 0 || url.rfind("ws", 0) == 0 ||
                         url.rfind("ftp:", 0) == 0;
    if (network && initiator != "not an origin") urls.push_back(url);
  }
  return urls;
}

// `html` as Chromium renders it from disk; with `probe`, a copy of it with kProbe appended (see Rendered::probe).
Rendered render(std::string html, const test::TempDir& dir, bool probe = false) {
  Rendered r;
  if (probe) {
    std::string page = test::read_bytes(html);
    const std::size_t end = page.rfind("</body>");
    page.insert(end == std::string::npos ? page.size() : end, "<script>" + std::string(test::kProbe) + "</script>\n");
    html = dir.file("probed.html");
    test::write_bytes(html, page);
  }
  const std::string png = dir.file("shot.png"), net = dir.file("net.json");
  r.run = test::run("/usr/bin/timeout",
                    {"60", chromium_path(), "--headless=new", "--no-sandbox", "--use-angle=swiftshader",
                     "--enable-unsafe-swiftshader", "--hide-scrollbars", "--window-size=1200,1100",
                     "--user-data-dir=" + dir.file("profile"), "--no-first-run", "--disable-extensions",
                     "--disable-background-networking", "--disable-component-update", "--disable-sync",
                     "--disable-default-apps", "--host-resolver-rules=MAP * ~NOTFOUND", "--log-net-log=" + net,
                     "--screenshot=" + png, "--dump-dom", "file://" + html});
  r.dom = r.run.out;
  r.screenshot = cv::imread(png, cv::IMREAD_COLOR);
  r.page_requests = page_requests(net);
  r.probe = test::embedded_json(r.dom, test::kProbeId);
  return r;
}

std::string body_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  const std::string body = dom.substr(0, dom.find('>', dom.find("<body")) + 1);
  if (std::regex_search(body, m, std::regex(name + "=\"([^\"]*)\""))) return m[1];
  return "";
}

// Half a unit of the last digit shown ("0.0123" -> 5e-5, "1.5e+03" -> 50).
double shown_precision(const std::string& text) {
  const std::size_t e = text.find_first_of("eE");
  const std::string mantissa = text.substr(0, e);
  const std::size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  const int exponent = e == std::string::npos ? 0 : std::stoi(text.substr(e + 1));
  return 0.5 * std::pow(10.0, exponent - decimals) * (1.0 + 1e-9);
}

// Every <td data-json="pointer">text</td>: the text is the JSON's value. Returns the number of cells checked.
std::size_t check_tied_cells(const std::string& dom, const nlohmann::json& json) {
  const std::regex cell("<td[^>]*data-json=\"([^\"]+)\"[^>]*>([^<]*)</td>");
  std::size_t checked = 0;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), cell); it != std::sregex_iterator(); ++it) {
    const std::string pointer = (*it)[1], text = (*it)[2];
    ++checked;
    const nlohmann::json::json_pointer ptr(pointer);
    if (!json.contains(ptr)) {
      ADD_FAILURE() << pointer << " is not in the JSON";
      continue;
    }
    const nlohmann::json& value = json.at(ptr);
    if (value.is_number()) {
      EXPECT_NEAR(std::stod(text), value.get<double>(), shown_precision(text)) << pointer;
    } else if (value.is_boolean()) {
      EXPECT_EQ(text, value.get<bool>() ? "true" : "false") << pointer;
    } else {
      EXPECT_EQ(text, value.is_string() ? value.get<std::string>() : value.dump()) << pointer;
    }
  }
  return checked;
}

nlohmann::json embedded_result(const std::string& dom) { return test::embedded_json(dom, "conform-result"); }

int count_pixels(const cv::Mat& image, const std::function<bool(const cv::Vec3b&)>& match) {
  int n = 0;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) n += match(image.at<cv::Vec3b>(y, x)) ? 1 : 0;
  }
  return n;
}

bool near(const cv::Vec3b& bgr, int r, int g, int b, int tolerance) {
  return std::abs(bgr[2] - r) <= tolerance && std::abs(bgr[1] - g) <= tolerance && std::abs(bgr[0] - b) <= tolerance;
}

class ReportBrowser : public ::testing::TestWithParam<ReportCase> {};

TEST_P(ReportBrowser, RendersFromDiskWithTheJsonsNumbers) {
  if (chromium_path().empty()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  const ReportCase& c = GetParam();
  test::TempDir dir;
  for (const auto& setup : c.setup) {
    std::vector<std::string> args;
    for (const std::string& a : setup) args.push_back(expand(a, dir));
    const auto g = test::run(CONFORM_EXE, args);
    ASSERT_EQ(g.exit_code, 0) << g.err;
  }
  std::vector<std::string> args;
  for (const std::string& a : c.command) args.push_back(expand(a, dir));
  const auto job = test::run(CONFORM_EXE, args);
  ASSERT_EQ(job.exit_code, c.exit_code) << job.err;
  const nlohmann::json json = nlohmann::json::parse(job.out);
  const std::string html = dir.file("report.html");
  ASSERT_TRUE(std::filesystem::exists(html));

  const Rendered r = render(html, dir, true);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.err.substr(0, 2000);
  ASSERT_FALSE(r.screenshot.empty()) << "no screenshot";
  EXPECT_EQ(body_attribute(r.dom, "data-scene-error"), "");
  EXPECT_NE(body_attribute(r.dom, "data-scene-drawn"), "") << "the view's script did not finish";
  // 1. The canvas (its rectangle from the page) was cleared to the view's background and has geometry on it.
  int x = 0, y = 0, w = 0, h = 0;
  ASSERT_EQ(std::sscanf(body_attribute(r.dom, "data-view-rect").c_str(), "%d,%d,%d,%d", &x, &y, &w, &h), 4);
  const cv::Rect view = cv::Rect(x + 2, y + 2, w - 4, h - 4) & cv::Rect(0, 0, r.screenshot.cols, r.screenshot.rows);
  ASSERT_GT(view.height, 300) << "the view is below the screenshot";
  const cv::Mat canvas = r.screenshot(view);
  const int background = count_pixels(canvas, [](const cv::Vec3b& p) { return near(p, 244, 246, 249, 2); });
  const int drawn = count_pixels(canvas, [](const cv::Vec3b& p) { return !near(p, 244, 246, 249, 12); });
  EXPECT_GT(background, static_cast<int>(0.2 * view.area())) << "the canvas was not cleared: no WebGL?";
  EXPECT_GT(drawn, 2000) << "nothing drawn on the canvas";
  // 2. The deviation map's colours: its in-tolerance green, and the red of the bump above it.
  if (c.deviation_colours) {
    EXPECT_GT(count_pixels(canvas, [](const cv::Vec3b& p) { return near(p, 0, 190, 60, 45); }), 500);
    EXPECT_GT(count_pixels(canvas, [](const cv::Vec3b& p) { return p[2] > 190 && p[1] < 150 && p[0] < 90; }), 20);
  }
  // 3. No network request from the page.
  EXPECT_TRUE(r.page_requests.empty()) << r.page_requests.front();
  // 4. The tables' numbers and the embedded JSON are the --json output.
  EXPECT_GE(check_tied_cells(r.dom, json), c.min_tied_cells);
  EXPECT_EQ(embedded_result(r.dom), json);
  // 5. What the reader sees.
  test::check_what_the_reader_sees(c.job, c.reader, r.probe, json);

  const char* update = std::getenv("CONFORM_UPDATE_DOCS_IMAGES");
  if (update != nullptr && std::string(update) == "1") {
    cv::Mat small;
    cv::resize(r.screenshot(cv::Rect(0, 0, 1200, std::min(1000, r.screenshot.rows))), small, cv::Size(), 0.75, 0.75,
               cv::INTER_AREA);
    cv::imwrite(std::string(CONFORM_SOURCE_DIR) + "/docs/images/report_" + c.job + ".png", small,
                {cv::IMWRITE_PNG_COMPRESSION, 9});
  }
}

INSTANTIATE_TEST_SUITE_P(ReportBrowserMatrix, ReportBrowser, ::testing::ValuesIn(kReports),
                         [](const ::testing::TestParamInfo<ReportCase>& p) { return p.param.job; });

// The network check can fail: a page that loads an image and fetches a script over http(s) is caught.
TEST(ReportBrowserMatrix, NetworkCheckSeesAFetch) {
  if (chromium_path().empty()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  test::TempDir dir;
  test::write_bytes(dir.file("fetch.html"),
                    "<html><body><img src=\"http://example.invalid/a.png\"><script>"
                    "fetch('https://cdn.example.invalid/three.js').catch(function () {});</script></body></html>");
  const Rendered r = render(dir.file("fetch.html"), dir);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.err.substr(0, 2000);
  EXPECT_EQ(r.page_requests.size(), 2u);
}

// Every kind of scene object the report module offers (the other jobs' pages use them): points with one colour,
// a mesh with per-vertex colours, a closed polyline and arrows, far from the origin; the page draws them all, each in
// its colour.
TEST(ReportBrowserMatrix, EveryObjectKindDraws) {
  if (chromium_path().empty()) GTEST_SKIP() << "chromium is not installed (scripts/setup.sh installs it)";
  test::TempDir dir;
  html::Page page;
  page.job = "scene";
  page.verdict = {html::Level::kOk, "every object kind"};
  const Eigen::Vector3d far(250000.0, -80000.0, 1200.0);
  std::vector<Eigen::Vector3d> ring, grid, origins, directions;
  for (int i = 0; i < 72; ++i) {
    const double a = i * M_PI / 36.0;
    ring.push_back(far + Eigen::Vector3d(60.0 * std::cos(a), 60.0 * std::sin(a), 0.0));
    origins.push_back(far + Eigen::Vector3d(40.0 * std::cos(a), 40.0 * std::sin(a), 0.0));
    directions.emplace_back(0.0, 0.0, 1.0);
  }
  for (int i = -20; i <= 20; ++i) {
    for (int j = -20; j <= 20; ++j) grid.push_back(far + Eigen::Vector3d(i, j, 30.0));
  }
  Mesh square;
  square.vertices = {far + Eigen::Vector3d(-30, -30, -10), far + Eigen::Vector3d(30, -30, -10),
                     far + Eigen::Vector3d(30, 30, -10), far + Eigen::Vector3d(-30, 30, -10)};
  square.faces = {{0, 1, 2}, {0, 2, 3}};
  page.scene.add_points("grid", grid, html::Rgb{20, 20, 220}, 3.0);
  page.scene.add_mesh("square", square.vertices, square.faces, html::kGrey, 1.0,
                      {{230, 20, 20}, {230, 20, 20}, {230, 20, 20}, {230, 20, 20}});
  page.scene.add_polyline("ring", ring, html::Rgb{20, 160, 20}, true);
  page.scene.add_arrows("normals", origins, directions, 25.0, html::Rgb{240, 140, 0});
  html::write_html(dir.file("scene.html"), page);
  const Rendered r = render(dir.file("scene.html"), dir);
  ASSERT_EQ(r.run.exit_code, 0) << r.run.err.substr(0, 2000);
  ASSERT_FALSE(r.screenshot.empty());
  EXPECT_EQ(body_attribute(r.dom, "data-scene-error"), "");
  EXPECT_EQ(body_attribute(r.dom, "data-scene-drawn"), "4");
  int x = 0, y = 0, w = 0, h = 0;
  ASSERT_EQ(std::sscanf(body_attribute(r.dom, "data-view-rect").c_str(), "%d,%d,%d,%d", &x, &y, &w, &h), 4);
  const cv::Mat canvas = r.screenshot(cv::Rect(x + 2, y + 2, w - 4, h - 4) & cv::Rect(0, 0, r.screenshot.cols, r.screenshot.rows));
  // Lit, the red mesh is darker than its colour; unlit points, lines and arrows keep theirs.
  EXPECT_GT(count_pixels(canvas, [](const cv::Vec3b& p) { return p[2] > 100 && p[1] < 40 && p[0] < 40; }), 500) << "mesh";
  EXPECT_GT(count_pixels(canvas, [](const cv::Vec3b& p) { return near(p, 20, 20, 220, 40); }), 200) << "points";
  EXPECT_GT(count_pixels(canvas, [](const cv::Vec3b& p) { return near(p, 20, 160, 20, 50); }), 50) << "polyline";
  EXPECT_GT(count_pixels(canvas, [](const cv::Vec3b& p) { return near(p, 240, 140, 0, 50); }), 50) << "arrows";
  EXPECT_TRUE(r.page_requests.empty());
}

}  // namespace
}  // namespace conform
