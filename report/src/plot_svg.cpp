// Plots as inline SVG: a fixed 720 x 300 canvas (scaled by CSS), axes with 1-2-5 ticks, bars or lines, bands, marks.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "report_detail.h"

namespace conform::html::detail {
namespace {

constexpr double kWidth = 720, kHeight = 300;
constexpr double kLeft = 70, kRight = 20, kTop = 34, kBottom = 52;

std::string css(const Rgb& c) {
  char text[16];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", c[0], c[1], c[2]);
  return text;
}

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  void pad() {
    if (!(lo <= hi)) lo = 0.0, hi = 1.0;
    if (hi - lo <= 0.0) {
      const double d = std::max(std::abs(lo) * 0.05, 1e-9);
      lo -= d, hi += d;
    }
  }
};

struct Frame {
  Range x, y;
  double px(double v) const { return kLeft + (v - x.lo) / (x.hi - x.lo) * (kWidth - kLeft - kRight); }
  double py(double v) const { return kHeight - kBottom - (v - y.lo) / (y.hi - y.lo) * (kHeight - kTop - kBottom); }
};

Frame frame_of(const Plot& plot) {
  Frame f;
  for (const Bar& b : plot.bars) f.x.add(b.lo), f.x.add(b.hi), f.y.add(b.count);
  if (!plot.bars.empty()) f.y.add(0.0);
  for (const Series& s : plot.series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) f.x.add(s.x[i]), f.y.add(s.y[i]);
    }
  }
  if (plot.x_band) f.x.add(plot.x_band->lo), f.x.add(plot.x_band->hi);
  if (plot.y_band) f.y.add(plot.y_band->lo), f.y.add(plot.y_band->hi);
  f.x.pad();
  f.y.pad();
  const double ymargin = 0.06 * (f.y.hi - f.y.lo);
  f.y.hi += ymargin;
  if (plot.bars.empty()) f.y.lo -= ymargin;
  return f;
}

void axes(std::string& out, const Frame& f, const Plot& plot) {
  const double bottom = kHeight - kBottom, right = kWidth - kRight;
  const double xs = nice_step(f.x.hi - f.x.lo, 8), ys = nice_step(f.y.hi - f.y.lo, 5);
  for (double v = std::ceil(f.x.lo / xs) * xs; v <= f.x.hi + 1e-9 * xs; v += xs) {
    const double shown = std::abs(v) < 0.5 * xs ? 0.0 : v;
    out += "<line class=\"grid\" x1=\"" + num(f.px(v)) + "\" y1=\"" + num(kTop) + "\" x2=\"" + num(f.px(v)) +
           "\" y2=\"" + num(bottom) + "\"/><text x=\"" + num(f.px(v)) + "\" y=\"" + num(bottom + 16) +
           "\" text-anchor=\"middle\">" + format_g(shown, 6) + "</text>";
  }
  for (double v = std::ceil(f.y.lo / ys) * ys; v <= f.y.hi + 1e-9 * ys; v += ys) {
    const double shown = std::abs(v) < 0.5 * ys ? 0.0 : v;
    out += "<line class=\"grid\" x1=\"" + num(kLeft) + "\" y1=\"" + num(f.py(v)) + "\" x2=\"" + num(right) +
           "\" y2=\"" + num(f.py(v)) + "\"/><text x=\"" + num(kLeft - 6) + "\" y=\"" + num(f.py(v) + 4) +
           "\" text-anchor=\"end\">" + format_g(shown, 6) + "</text>";
  }
  out += "<rect class=\"frame\" x=\"" + num(kLeft) + "\" y=\"" + num(kTop) + "\" width=\"" + num(right - kLeft) +
         "\" height=\"" + num(bottom - kTop) + "\"/>";
  out += "<text x=\"" + num((kLeft + right) / 2) + "\" y=\"" + num(kHeight - 14) + "\" text-anchor=\"middle\">" +
         escape_html(plot.x_label) + "</text>";
  out += "<text x=\"14\" y=\"" + num((kTop + bottom) / 2) + "\" text-anchor=\"middle\" transform=\"rotate(-90 14 " +
         num((kTop + bottom) / 2) + ")\">" + escape_html(plot.y_label) + "</text>";
  out += "<text class=\"title\" x=\"" + num(kWidth / 2) + "\" y=\"18\" text-anchor=\"middle\">" +
         escape_html(plot.title) + "</text>";
}

void bands(std::string& out, const Frame& f, const Plot& plot) {
  const double bottom = kHeight - kBottom, right = kWidth - kRight;
  if (plot.x_band) {
    const std::string kind = plot.x_band->reject ? " reject" : "";
    const double a = std::clamp(f.px(plot.x_band->lo), kLeft, right), b = std::clamp(f.px(plot.x_band->hi), kLeft, right);
    out += "<rect class=\"band" + kind + "\" x=\"" + num(a) + "\" y=\"" + num(kTop) + "\" width=\"" + num(b - a) + "\" height=\"" +
           num(bottom - kTop) + "\"><title>" + escape_html(plot.x_band->label) + "</title></rect>";
    // Right of the band, or inside its right edge when the label (about 6 px a character) would leave the frame.
    const bool fits = b + 3 + 6.0 * static_cast<double>(plot.x_band->label.size()) <= right;
    out += "<text class=\"band-label" + kind + "\" x=\"" + num(fits ? b + 3 : b - 3) + "\" y=\"" + num(kTop + 12) +
           "\"" + (fits ? "" : " text-anchor=\"end\"") + ">" + escape_html(plot.x_band->label) + "</text>";
  }
  if (plot.y_band) {
    const std::string kind = plot.y_band->reject ? " reject" : "";
    const double a = std::clamp(f.py(plot.y_band->hi), kTop, bottom), b = std::clamp(f.py(plot.y_band->lo), kTop, bottom);
    out += "<rect class=\"band" + kind + "\" x=\"" + num(kLeft) + "\" y=\"" + num(a) + "\" width=\"" + num(right - kLeft) +
           "\" height=\"" + num(b - a) + "\"><title>" + escape_html(plot.y_band->label) + "</title></rect>";
    // Inside the band, at its top (above the frame's top it would meet the title).
    out += "<text class=\"band-label" + kind + "\" x=\"" + num(kLeft + 4) + "\" y=\"" + num(std::min(a + 12, b - 2)) +
           "\">" + escape_html(plot.y_band->label) + "</text>";
  }
}

void series(std::string& out, const Frame& f, const Plot& plot) {
  double legend_y = kTop + 14;
  for (const Series& s : plot.series) {
    std::string path;
    bool pen_down = false;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        pen_down = false;
        continue;
      }
      path += (pen_down ? "L" : "M") + num(f.px(s.x[i])) + " " + num(f.py(s.y[i]));
      pen_down = true;
      if (s.dots) {
        out += "<circle cx=\"" + num(f.px(s.x[i])) + "\" cy=\"" + num(f.py(s.y[i])) + "\" r=\"2\" fill=\"" +
               css(s.colour) + "\"/>";
      }
    }
    out += "<path class=\"line\" stroke=\"" + css(s.colour) + "\" d=\"" + path + "\"/>";
    if (!s.name.empty()) {
      const double x = kWidth - kRight - 150;
      out += "<line x1=\"" + num(x) + "\" y1=\"" + num(legend_y - 4) + "\" x2=\"" + num(x + 18) + "\" y2=\"" +
             num(legend_y - 4) + "\" stroke=\"" + css(s.colour) + "\" stroke-width=\"2\"/><text x=\"" + num(x + 22) +
             "\" y=\"" + num(legend_y) + "\">" + escape_html(s.name) + "</text>";
      legend_y += 15;
    }
  }
}

}  // namespace

std::string plot_svg(const Plot& plot) {
  const Frame f = frame_of(plot);
  std::string out = "<svg class=\"plot\" viewBox=\"0 0 720 300\" role=\"img\">";
  bands(out, f, plot);
  axes(out, f, plot);
  const double bottom = kHeight - kBottom;
  for (std::size_t i = 0; i < plot.bars.size(); ++i) {
    const Bar& b = plot.bars[i];
    if (!(b.count > 0)) continue;
    // The end bars also hold the values beyond the axis: outlined, and labelled below.
    const bool overflow = (i == 0 && plot.below > 0) || (i + 1 == plot.bars.size() && plot.above > 0);
    const double x0 = f.px(b.lo), x1 = f.px(b.hi), top = f.py(b.count);
    out += "<rect class=\"bar" + std::string(overflow ? " overflow" : "") + "\" x=\"" + num(x0 + 0.5) + "\" y=\"" +
           num(top) + "\" width=\"" + num(std::max(x1 - x0 - 1.0, 0.5)) + "\" height=\"" + num(bottom - top) +
           "\" fill=\"" + css(b.colour) + "\"><title>[" + format_g(b.lo, 5) + ", " + format_g(b.hi, 5) +
           "): " + format_g(b.count, 10) + "</title></rect>";
  }
  if (!plot.bars.empty() && plot.below > 0) {
    out += "<text class=\"overflow-label\" x=\"" + num(kLeft + 4) + "\" y=\"" + num(kTop + 26) + "\">&#9664; " +
           std::to_string(plot.below) + " below " + format_g(plot.bars.front().lo, 3) + " (in the first bar)</text>";
  }
  if (!plot.bars.empty() && plot.above > 0) {
    out += "<text class=\"overflow-label\" x=\"" + num(kWidth - kRight - 4) + "\" y=\"" + num(kTop + 26) +
           "\" text-anchor=\"end\">" + std::to_string(plot.above) + " above " + format_g(plot.bars.back().hi, 3) +
           " (in the last bar) &#9654;</text>";
  }
  for (double m : plot.x_marks) {
    if (m < f.x.lo || m > f.x.hi) continue;
    out += "<line class=\"mark\" x1=\"" + num(f.px(m)) + "\" y1=\"" + num(kTop) + "\" x2=\"" + num(f.px(m)) +
           "\" y2=\"" + num(bottom) + "\"/>";
  }
  series(out, f, plot);
  out += "</svg>";
  if (!plot.note.empty()) out += "<p class=\"note\">" + escape_html(plot.note) + "</p>";
  return out;
}

namespace {

// Words of `text` on lines of at most `width` characters (a word longer than that stands alone).
std::vector<std::string> wrapped(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::string line, word;
  const auto flush_word = [&] {
    if (word.empty()) return;
    if (!line.empty() && line.size() + 1 + word.size() > width) lines.push_back(line), line.clear();
    line += (line.empty() ? "" : " ") + word;
    word.clear();
  };
  for (char c : text) {
    if (c == ' ') {
      flush_word();
    } else {
      word += c;
    }
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::vector<double> spread_labels(std::vector<double> y, double gap, double lo, double hi) {
  // y ascending: push each label down below the one above it, then back up from the bottom limit.
  for (std::size_t i = 1; i < y.size(); ++i) y[i] = std::max(y[i], y[i - 1] + gap);
  if (!y.empty() && y.back() > hi) y.back() = hi;
  for (std::size_t i = y.size(); i-- > 1;) y[i - 1] = std::min(y[i - 1], y[i] - gap);
  if (!y.empty() && y.front() < lo) {
    y.front() = lo;
    for (std::size_t i = 1; i < y.size(); ++i) y[i] = std::max(y[i], y[i - 1] + gap);
  }
  return y;
}

}  // namespace

std::string colour_bar_svg(const ColourBar& bar) {
  // Vertical, max at the top; 150 wide (the side column), as tall as the wrapped title and caption need.
  constexpr double x = 10, w = 22, h = 210, kWide = 150, kLine = 14, kLabelGap = 13;
  const std::vector<std::string> title = wrapped(bar.title, 22), caption = wrapped(bar.map, 28);
  const double top = 8 + kLine * static_cast<double>(title.size()) + 6;
  const double height = top + h + 10 + 12 * static_cast<double>(caption.size()) + 4;
  const double span = bar.max - bar.min > 0.0 ? bar.max - bar.min : 1.0;
  const auto y = [&](double v) { return top + (bar.max - v) / span * h; };
  std::string out = "<svg class=\"colour-bar\" viewBox=\"0 0 " + num(kWide) + " " + num(height) + "\" width=\"" +
                    num(kWide) + "\" height=\"" + num(height) + "\">";
  out += "<defs><linearGradient id=\"cbar\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">";
  for (const auto& [v, c] : bar.stops) {
    out += "<stop offset=\"" + num((v - bar.min) / span) + "\" stop-color=\"" + css(c) + "\"/>";
  }
  out += "</linearGradient></defs>";
  for (std::size_t i = 0; i < title.size(); ++i) {
    out += "<text x=\"4\" y=\"" + num(8 + kLine * static_cast<double>(i + 1) - 3) + "\" class=\"title\">" +
           escape_html(title[i]) + "</text>";
  }
  out += "<rect x=\"" + num(x) + "\" y=\"" + num(top) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
         "\" fill=\"url(#cbar)\" stroke=\"#444\"/>";
  std::vector<double> labels = {bar.max, 0.5 * (bar.min + bar.max), bar.min};
  if (bar.band) {
    const double a = y(bar.band->second), b = y(bar.band->first);
    out += "<rect x=\"" + num(x - 4) + "\" y=\"" + num(a) + "\" width=\"" + num(w + 8) + "\" height=\"" + num(b - a) +
           "\" fill=\"none\" stroke=\"#000\" stroke-dasharray=\"3 2\"/>";
    labels = {bar.max, bar.band->second, bar.band->first, bar.min};
  }
  // Each label beside its value's height, moved apart where they would overlap, with a leader to its tick.
  std::vector<double> ticks;
  for (double v : labels) ticks.push_back(y(v));
  const std::vector<double> at = spread_labels(ticks, kLabelGap, top - 4, top + h + 4);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    out += "<line class=\"tick\" x1=\"" + num(x + w) + "\" y1=\"" + num(ticks[i]) + "\" x2=\"" + num(x + w + 4) +
           "\" y2=\"" + num(at[i]) + "\" stroke=\"#444\"/>";
    out += "<text class=\"label\" x=\"" + num(x + w + 6) + "\" y=\"" + num(at[i] + 4) + "\">" +
           format_g(labels[i], 4) + "</text>";
  }
  for (std::size_t i = 0; i < caption.size(); ++i) {
    out += "<text class=\"caption\" x=\"4\" y=\"" + num(top + h + 10 + 12 * static_cast<double>(i + 1) - 2) +
           "\" font-size=\"10\">" + escape_html(caption[i]) + "</text>";
  }
  return out + "</svg>";
}

}  // namespace conform::html::detail
