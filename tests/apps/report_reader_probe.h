#pragma once
// What a reader of a report page sees, measured in the rendered page (tests/apps/report_browser_test.cpp): kProbe,
// appended to the page, writes its measurements as JSON into <script type="application/json" id="conform-probe">;
// check_what_the_reader_sees() judges them. The view frames the geometry, every layer has a colour swatch, the colour
// bar's labels do not overlap and its texts stay inside it, a histogram with outliers still has many bars (the
// outliers in labelled end bars), a click on a point shows its coordinates (and value), the worst points have
// callouts, and a band marking a reject zone is not green.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace conform::test {

// What one page must show.
struct ReaderAids {
  std::string value_label;     // a click on a point shows this value (empty: coordinates only)
  int min_callouts = 0;        // labelled callouts shown in the view, at least
  int min_histogram_bars = 0;  // non-empty bars of the page's histogram, at least (0: no histogram)
};

inline constexpr const char* kProbeId = "conform-probe";

// Appended to a report (before </body>, after the page's own scripts): measures what the reader sees and writes it,
// as JSON, into <script type="application/json" id="conform-probe">.
inline constexpr const char* kProbe = R"js(
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

inline bool overlap(const nlohmann::json& a, const nlohmann::json& b) {  // [left, top, right, bottom], half a pixel slack
  return a[0].get<double>() < b[2].get<double>() - 0.5 && b[0].get<double>() < a[2].get<double>() - 0.5 &&
         a[1].get<double>() < b[3].get<double>() - 0.5 && b[1].get<double>() < a[3].get<double>() - 0.5;
}

// "rgb(214, 39, 40)" -> {214, 39, 40}.
inline std::array<int, 3> css_rgb(const std::string& text) {
  std::array<int, 3> c{-1, -1, -1};
  std::sscanf(text.c_str(), "rgb(%d, %d, %d)", &c[0], &c[1], &c[2]);
  return c;
}

// 5. What the reader sees, from kProbe's measurements.
inline void check_what_the_reader_sees(const std::string& job, const ReaderAids& expect, const nlohmann::json& p,
                                       const nlohmann::json& json) {
  ASSERT_TRUE(p.is_object()) << "the probe did not run";
  // The view frames the geometry: its drawn pixels span most of the canvas's width or height.
  const nlohmann::json& canvas = p["canvas"];
  const double span_x = canvas["span_x"].get<double>() / canvas["width"].get<double>();
  const double span_y = canvas["span_y"].get<double>() / canvas["height"].get<double>();
  EXPECT_TRUE(span_x > 0.7 || span_y > 0.7) << "the geometry spans " << span_x << " x " << span_y << " of the canvas";
  EXPECT_GT(span_x * span_y, 0.25) << "the geometry's rectangle covers " << 100 * span_x * span_y << " % of the canvas";
  std::printf("%s: the geometry spans %.2f x %.2f of the canvas, %.1f %% of its pixels drawn\n", job.c_str(), span_x,
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
  if (expect.min_histogram_bars > 0) {
    ASSERT_FALSE(p["histograms"].empty());
    const nlohmann::json& h = p["histograms"][0];
    EXPECT_GE(h["bars"].get<int>(), expect.min_histogram_bars);
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
  if (!expect.value_label.empty()) {
    EXPECT_EQ(m[1].str(), p["clicked"].get<std::string>());
    EXPECT_EQ(m[6].str(), expect.value_label);
    if (json.contains("min_mm") && json.contains("max_mm")) {
      const double v = std::stod(m[7].str());
      EXPECT_GE(v, json["min_mm"].get<double>() - 1e-4);
      EXPECT_LE(v, json["max_mm"].get<double>() + 1e-4);
    }
  }
  // Callouts at the worst points, apart from each other; the first at the largest |deviation|.
  const nlohmann::json& callouts = p["callouts"];
  EXPECT_GE(static_cast<int>(callouts.size()), expect.min_callouts);
  for (std::size_t i = 0; i < callouts.size(); ++i) {
    for (std::size_t j = i + 1; j < callouts.size(); ++j) {
      EXPECT_FALSE(overlap(callouts[i]["box"], callouts[j]["box"])) << callouts[i] << " and " << callouts[j];
    }
  }
  if (expect.min_callouts > 0 && !callouts.empty() && json.contains("max_mm") && json.contains("min_mm")) {
    const double worst = std::max(std::abs(json["min_mm"].get<double>()), std::abs(json["max_mm"].get<double>()));
    double first = 0.0;
    ASSERT_EQ(std::sscanf(callouts[0]["text"].get<std::string>().c_str(), "1: %lf mm", &first), 1) << callouts[0];
    EXPECT_NEAR(std::abs(first), worst, 6e-4);
  }
}

}  // namespace conform::test
