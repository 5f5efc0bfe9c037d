// The HTML reports (--report, docs/report.md) rendered in a real browser: headless Chromium with software WebGL
// (SwiftShader) opens each report from disk, and the test asserts from its screenshot and its DOM that
//  1. the 3D view drew: the canvas was cleared to the view's background and has geometry on it,
//  2. compare's and align's views show the deviation map's colours (its green, and the red of the bump),
//  3. the page asked for nothing over the network: Chromium's net log holds no http(s)/ws request from the page
//     (the page's requests carry its file:// origin, "null"; Chromium's own background requests "not an origin";
//     NetworkCheckSeesAFetch shows that a page which does fetch is caught),
//  4. the numbers in the page's tables are the job's --json output (each cell tied to a JSON pointer, equal to
//     the shown precision), and the JSON embedded in the page is that output,
//  5. what a reader sees, measured in the page by a probe script the test appends (kProbe): the view frames the
//     geometry (its drawn pixels span most of the canvas), every layer has a colour swatch, the colour bar's labels
//     do not overlap and its texts stay inside it, a histogram of data with outliers still has many bars (the
//     outliers in labelled end bars), a click on a point shows its coordinates (and value), the worst points have
//     callouts, and a band marking a reject zone is not green.
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
  std::string value_label;         // a click on a point shows this value (empty: coordinates only)
  int min_callouts = 0;            // labelled callouts shown in the view, at least
  int min_histogram_bars = 0;      // non-empty bars of the page's histogram, at least (0: no histogram)
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
     0, true, 12, "deviation (mm)", 3, 15},
    {"align",
     {with(kPatch, {"--edge", "2.5", "--out", "{dir}/ref.ply"}),
      with(kPatch, {"--edge", "2", "--bump", "0,0,1.5,15", "--noise", "0.02", "--out", "{dir}/scan.ply"})},
     {"align", "--scan", "{dir}/scan.ply", "--reference", "{dir}/ref.ply", "--report", "{report}", "--json"}, 0, true,
     20, "deviation (mm)", 3, 15},
    {"fit_cylinder",
     {{"generate", "tube", "--quiet", "--radius", "150", "--arc-deg", "120", "--length", "150", "--edge", "3",
       "--noise", "0.05", "--outliers", "0.02", "--out", "{dir}/tube.ply"}},
     {"fit-cylinder", "--input", "{dir}/tube.ply", "--quiet", "--report", "{report}", "--json"}, 0, false, 15,
     "residual (mm)", 5, 25},
    {"sicp",
     {{"generate", "plate", "--out", "{dir}/p.ply", "--scan-points", "8000", "--contour-spacing", "2",
       "--surface-edge", "4", "--quiet"}},
     {"sicp", "--contour", "{dir}/p.contour.csv", "--scan", "{dir}/p.ply", "--trajectory", "{dir}/p.trajectory.csv",
      "--surface", "{dir}/p.nominal.ply", "--truth", "{dir}/p.truth.csv", "--quiet", "--report", "{report}", "--json"},
     0, false, 100, "", 0, 0},
    {"profile",
     {{"generate", "profile", "--out", "{dir}/p.csv", "--length", "3000", "--bow", "40", "--holes", "3",
       "--marking-line"}},
     {"profile", "--edge", "{dir}/p.csv", "--features", "{dir}/p.features.csv", "--report", "{report}", "--json"}, 0,
     false, 20, "", 0, 0},
    {"tube_joint",
     {{"generate", "tube-joint", "--out-leg", "{dir}/leg.ply", "--out-stub", "{dir}/stub.ply", "--out-truth",
       "{dir}/truth.csv", "--leg-radius", "300", "--stub-radius", "160", "--wall", "10", "--edge", "10",
       "--pitch-deg", "60", "--offset", "30", "--protrusion", "540", "--noise", "0.2"}},
     {"tube-joint", "--leg", "{dir}/leg.ply", "--stub", "{dir}/stub.ply", "--pitch-deg", "60", "--offset", "30",
      "--protrusion", "540", "--step-deg", "2", "--groove-deg", "30,45,20,45", "--quiet", "--report", "{report}",
      "--json"},
     0, false, 14, "", 0, 0},
    {"saddle",
     {},
     {"saddle", "--R", "600", "--r", "150", "--pitch-deg", "60", "--offset", "100", "--start-pose-deg", "45",
      "--speed", "500", "--period", "0.004", "--report", "{report}", "--json"},
     0, false, 13, "", 0, 0},
    {"weld_layers",
     {{"generate", "eroded", "--out", "{dir}/blade.csv", "--crater", "0,0,15,2", "--crater", "35,10,8,1", "--crater",
       "55,-30,10,1.5"}},
     {"weld-layers", "--eroded", "{dir}/blade.csv", "--reference", "{dir}/blade.reference.csv", "--bead-spacing", "3",
      "--layer-height", "1", "--chord-error", "0.05", "--torch-distance", "2", "--report", "{report}", "--json"},
     0, false, 15, "depth (mm)", 3, 0},
};

// Appended to a report (before </body>, after the page's own scripts): measures what the reader sees and writes it,
// as JSON, into <script type="application/json" id="conform-probe">.
const char* const kProbe = R"js(
(function () {
  var r = {};
  function box(e) { var b = e.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; }
  function all(selector, f) { return Array.prototype.map.call(document.querySelectorAll(selector), f); }
  // The WebGL canvas before any click: the extent and share of the pixels that are not the clear colour.
  var canvas = document.querySelector('#conform-view canvas');
  if (canvas) {
    var c2 = document.createElement('canvas');
    c2.width = canvas.width;
    c2.height = canvas.height;
    var g = c2.getContext('2d');
    g.drawImage(canvas, 0, 0);
    var px = g.getImageData(0, 0, c2.width, c2.height).data, n = 0, x0 = 1e9, y0 = 1e9, x1 = -1, y1 = -1;
    for (var y = 0; y < c2.height; ++y) {
      for (var x = 0; x < c2.width; ++x) {
        var k = 4 * (y * c2.width + x);
        if (Math.abs(px[k] - 244) + Math.abs(px[k + 1] - 246) + Math.abs(px[k + 2] - 249) <= 24) continue;
        ++n;
        x0 = Math.min(x0, x), x1 = Math.max(x1, x), y0 = Math.min(y0, y), y1 = Math.max(y1, y);
      }
    }
    r.canvas = {width: c2.width, height: c2.height, drawn: n, span_x: Math.max(0, x1 - x0 + 1), span_y: Math.max(0, y1 - y0 + 1)};
  }
  r.swatches = all('input[data-layer]', function (i) {
    var s = i.parentNode.querySelector('.swatch');
    if (!s) return '';
    var st = getComputedStyle(s);
    return st.backgroundImage !== 'none' ? st.backgroundImage : st.backgroundColor;
  });
  var bar = document.querySelector('svg.colour-bar');
  if (bar) {
    r.bar = box(bar);
    r.bar_labels = all('svg.colour-bar text:not(.title):not(.caption)', box);
    r.bar_texts = all('svg.colour-bar text', box);
  }
  r.histograms = [];
  all('svg.plot', function (svg) {
    var bars = svg.querySelectorAll('rect.bar');
    if (bars.length) {
      r.histograms.push({bars: bars.length, overflow_bars: svg.querySelectorAll('rect.bar.overflow').length,
                         overflow_labels: svg.querySelectorAll('.overflow-label').length});
    }
  });
  r.bands = all('svg.plot rect.band', function (b) { return {label: b.textContent, fill: getComputedStyle(b).fill}; });
  r.callouts = [];
  all('.callout', function (c) { if (c.style.display !== 'none') r.callouts.push({text: c.textContent, box: box(c)}); });
  // A click (pointer down and up at the same place) on a drawn vertex near the middle of the first layer with values
  // (else the first visible layer).
  if (window.conform_view) {
    var scene = JSON.parse(document.getElementById('conform-scene').textContent);
    var shown = scene.objects.filter(function (o) { return o.visible && o.count > 0; });
    var target = shown.filter(function (o) { return o.values; })[0] || shown[0];
    var view = box(document.getElementById('conform-view'));
    [0.5, 0.33, 0.25, 0.1, 0].some(function (f) {
      var at = window.conform_view.client_of(target.name, Math.floor(f * (target.count - 1)));
      if (!at || at[0] < view[0] + 5 || at[0] > view[2] - 5 || at[1] < view[1] + 5 || at[1] > view[3] - 5) return false;
      ['pointerdown', 'pointerup'].forEach(function (type) {
        canvas.dispatchEvent(new PointerEvent(type, {clientX: at[0], clientY: at[1], bubbles: true}));
      });
      r.clicked = target.name;
      return true;
    });
    var readout = document.getElementById('conform-readout');
    r.readout = readout.style.display === 'none' ? '' : readout.textContent;
  }
  var out = document.createElement('script');
  out.type = 'application/json';
  out.id = 'conform-probe';
  out.textContent = JSON.stringify(r);
  document.body.appendChild(out);
})();
)js";

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

// The JSON text of <script type="application/json" id="`id`"> in the DOM (null when there is none).
nlohmann::json script_json(const std::string& dom, const std::string& id) {
  const std::string open = "<script type=\"application/json\" id=\"" + id + "\">";
  const std::size_t start = dom.find(open);
  if (start == std::string::npos) return nullptr;
  const std::size_t end = dom.find("</script>", start);
  return nlohmann::json::parse(dom.substr(start + open.size(), end - start - open.size()), nullptr, false);
}

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
    page.insert(end == std::string::npos ? page.size() : end, "<script>" + std::string(kProbe) + "</script>\n");
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
  r.probe = script_json(r.dom, "conform-probe");
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

nlohmann::json embedded_result(const std::string& dom) { return script_json(dom, "conform-result"); }

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

bool overlap(const nlohmann::json& a, const nlohmann::json& b) {  // [left, top, right, bottom], half a pixel slack
  return a[0].get<double>() < b[2].get<double>() - 0.5 && b[0].get<double>() < a[2].get<double>() - 0.5 &&
         a[1].get<double>() < b[3].get<double>() - 0.5 && b[1].get<double>() < a[3].get<double>() - 0.5;
}

// "rgb(214, 39, 40)" -> {214, 39, 40}.
std::array<int, 3> css_rgb(const std::string& text) {
  std::array<int, 3> c{-1, -1, -1};
  std::sscanf(text.c_str(), "rgb(%d, %d, %d)", &c[0], &c[1], &c[2]);
  return c;
}

// 5. What the reader sees, from kProbe's measurements.
void check_what_the_reader_sees(const ReportCase& c, const nlohmann::json& p, const nlohmann::json& json) {
  ASSERT_TRUE(p.is_object()) << "the probe did not run";
  // The view frames the geometry: its drawn pixels span most of the canvas's width or height.
  const nlohmann::json& canvas = p["canvas"];
  const double span_x = canvas["span_x"].get<double>() / canvas["width"].get<double>();
  const double span_y = canvas["span_y"].get<double>() / canvas["height"].get<double>();
  EXPECT_TRUE(span_x > 0.7 || span_y > 0.7) << "the geometry spans " << span_x << " x " << span_y << " of the canvas";
  EXPECT_GT(span_x * span_y, 0.25) << "the geometry's rectangle covers " << 100 * span_x * span_y << " % of the canvas";
  std::printf("%s: the geometry spans %.2f x %.2f of the canvas, %.1f %% of its pixels drawn\n", c.job.c_str(), span_x,
              span_y, 100.0 * canvas["drawn"].get<double>() / (canvas["width"].get<double>() * canvas["height"].get<double>()));
  // Every layer has its colour beside its checkbox.
  ASSERT_FALSE(p["swatches"].empty());
  for (const auto& swatch : p["swatches"]) {
    const std::string text = swatch.get<std::string>();
    EXPECT_TRUE(text.find("gradient") != std::string::npos || (text.rfind("rgb(", 0) == 0)) << text;
  }
  // The colour bar: labels apart, every text inside the bar's box.
  if (p.contains("bar")) {
    const nlohmann::json& labels = p["bar_labels"];
    EXPECT_GE(labels.size(), 3u);
    for (std::size_t i = 0; i < labels.size(); ++i) {
      for (std::size_t j = i + 1; j < labels.size(); ++j) EXPECT_FALSE(overlap(labels[i], labels[j])) << i << ", " << j;
    }
    for (const auto& t : p["bar_texts"]) {
      EXPECT_GE(t[0].get<double>(), p["bar"][0].get<double>() - 0.5) << t.dump();
      EXPECT_LE(t[2].get<double>(), p["bar"][2].get<double>() + 0.5) << "a colour-bar text is cut off: " << t.dump();
    }
  }
  // The histogram shows the distribution, not one bar; outliers (if any) in labelled end bars.
  if (c.min_histogram_bars > 0) {
    ASSERT_FALSE(p["histograms"].empty());
    const nlohmann::json& h = p["histograms"][0];
    EXPECT_GE(h["bars"].get<int>(), c.min_histogram_bars);
    EXPECT_EQ(h["overflow_bars"].get<int>(), h["overflow_labels"].get<int>());
  }
  // A band that marks values not to be trusted is not shaded green; an acceptable range is.
  for (const auto& band : p["bands"]) {
    const std::array<int, 3> rgb = css_rgb(band["fill"].get<std::string>());
    const std::string label = band["label"].get<std::string>();
    if (label.find("untrusted") != std::string::npos) {
      EXPECT_GT(rgb[0], rgb[1]) << label << ": " << band["fill"];
    } else {
      EXPECT_GT(rgb[1], rgb[0]) << label << ": " << band["fill"];
    }
  }
  // A click on a point: its coordinates (and value) in the readout.
  const std::string readout = p.value("readout", "");
  std::smatch m;
  ASSERT_TRUE(std::regex_match(readout, m,
                               std::regex("(.+): x (-?[0-9]+\\.[0-9]{3}), y (-?[0-9]+\\.[0-9]{3}), z (-?[0-9]+\\.[0-9]{3}) mm"
                                          "(; (.+) ([-+][0-9]+\\.[0-9]{4}))?")))
      << "readout after a click on " << p.value("clicked", "?") << ": '" << readout << "'";
  if (!c.value_label.empty()) {
    EXPECT_EQ(m[1].str(), p["clicked"].get<std::string>());
    EXPECT_EQ(m[6].str(), c.value_label);
    if (json.contains("min_mm") && json.contains("max_mm")) {
      const double v = std::stod(m[7].str());
      EXPECT_GE(v, json["min_mm"].get<double>() - 1e-4);
      EXPECT_LE(v, json["max_mm"].get<double>() + 1e-4);
    }
  }
  // Callouts at the worst points, apart from each other; the first at the largest |deviation|.
  const nlohmann::json& callouts = p["callouts"];
  EXPECT_GE(static_cast<int>(callouts.size()), c.min_callouts);
  for (std::size_t i = 0; i < callouts.size(); ++i) {
    for (std::size_t j = i + 1; j < callouts.size(); ++j) {
      EXPECT_FALSE(overlap(callouts[i]["box"], callouts[j]["box"])) << callouts[i] << " and " << callouts[j];
    }
  }
  if (c.min_callouts > 0 && !callouts.empty() && json.contains("max_mm") && json.contains("min_mm")) {
    const double worst = std::max(std::abs(json["min_mm"].get<double>()), std::abs(json["max_mm"].get<double>()));
    double first = 0.0;
    ASSERT_EQ(std::sscanf(callouts[0]["text"].get<std::string>().c_str(), "1: %lf mm", &first), 1) << callouts[0];
    EXPECT_NEAR(std::abs(first), worst, 6e-4);
  }
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
  check_what_the_reader_sees(c, r.probe, json);

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
