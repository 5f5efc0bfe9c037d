#include "conform/pipelines/common/deviation_histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "conform/pipelines/common/deviation_colours.h"
#include "conform/report/png_writer.h"
#include "conform/report/plot.h"
#include "common/deviation_axis.h"

namespace conform {
namespace detail {


std::pair<double, double> deviation_axis(const std::vector<double>& sorted, const DeviationStatistics& s) {
  // Fences half the central-95 % span beyond the 2.5th and 97.5th percentiles: for normal noise they lie past the
  // 0.5th-99.5th percentiles (+-3.9 sigma against +-2.6), so only a thin, far tail (outliers) is cut off the axis.
  const double p2_5 = percentile_of_sorted(sorted, 2.5), p97_5 = percentile_of_sorted(sorted, 97.5);
  const double margin = 0.5 * (p97_5 - p2_5);
  double lo = std::min(std::max(percentile_of_sorted(sorted, 0.5), p2_5 - margin), 0.0);
  double hi = std::max(std::min(percentile_of_sorted(sorted, 99.5), p97_5 + margin), 0.0);
  if (s.tolerance_mm) {
    lo = std::min(lo, -1.3 * *s.tolerance_mm);
    hi = std::max(hi, 1.3 * *s.tolerance_mm);
  }
  const double span = hi - lo > 0.0 ? hi - lo : 2e-3;
  return {lo - 0.05 * span, hi + 0.05 * span};
}

}  // namespace detail

namespace {

constexpr int kBins = 60;
const cv::Rect kPlot(90, 90, kHistogramWidth - 90 - 30, kHistogramHeight - 90 - 70);  // x, y, width, height
const cv::Scalar kBlack(0, 0, 0), kDark(90, 90, 90), kGridGrey(225, 225, 225), kBandLine(40, 130, 0);

cv::Scalar bgr(const Rgb& c) { return cv::Scalar(c[2], c[1], c[0]); }

std::string format(const char* pattern, double value, int decimals = 0) {
  char text[64];
  std::snprintf(text, sizeof(text), pattern, decimals, value);
  return text;
}

void text(cv::Mat& img, const std::string& s, cv::Point at, double scale = 0.5, const cv::Scalar& c = kBlack,
          double align = 0.0) {  // align: 0 left, 0.5 centre, 1 right of `at`
  int baseline = 0;
  const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  at.x -= static_cast<int>(align * size.width);
  cv::putText(img, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, c, 1, cv::LINE_AA);
}

struct Axis {
  double lo, hi;
  int x(double v) const { return kPlot.x + static_cast<int>(std::lround((v - lo) / (hi - lo) * kPlot.width)); }
};

void dashed_vertical(cv::Mat& img, int x, const cv::Scalar& colour) {
  for (int y = kPlot.y; y < kPlot.y + kPlot.height; y += 10) {
    cv::line(img, {x, y}, {x, std::min(y + 6, kPlot.y + kPlot.height)}, colour, 2, cv::LINE_AA);
  }
}

void draw_band(cv::Mat& img, const Axis& axis, double t) {
  cv::Mat overlay = img.clone();
  cv::rectangle(overlay, cv::Point(axis.x(-t), kPlot.y), cv::Point(axis.x(t), kPlot.y + kPlot.height),
                cv::Scalar(200, 240, 200), cv::FILLED);
  cv::addWeighted(overlay, 0.6, img, 0.4, 0.0, img);
  const std::string limit = format("%.*f", t, t < 0.01 ? 4 : 3);
  text(img, "-" + limit, {axis.x(-t), kPlot.y - 8}, 0.45, kBandLine, 1.0);
  text(img, "+" + limit + " mm", {axis.x(t), kPlot.y - 8}, 0.45, kBandLine, 0.0);
}

void draw_axes(cv::Mat& img, const Axis& axis, int max_count) {
  const double step = html::nice_step(axis.hi - axis.lo, 8);
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  const int bottom = kPlot.y + kPlot.height;
  for (double v = std::ceil(axis.lo / step) * step; v <= axis.hi; v += step) {
    const double shown = std::abs(v) < 0.5 * step ? 0.0 : v;  // no "-0.00"
    cv::line(img, {axis.x(v), bottom}, {axis.x(v), bottom + 5}, kBlack, 1);
    text(img, format("%.*f", shown, decimals), {axis.x(v), bottom + 22}, 0.45, kBlack, 0.5);
  }
  const double count_step = std::max(1.0, html::nice_step(std::max(max_count, 1), 5));
  for (double c = 0; c <= max_count * 1.08; c += count_step) {
    const int y = bottom - static_cast<int>(std::lround(c / (max_count * 1.1) * kPlot.height));
    cv::line(img, {kPlot.x - 5, y}, {kPlot.x, y}, kBlack, 1);
    text(img, format("%.*f", c, 0), {kPlot.x - 9, y + 5}, 0.45, kBlack, 1.0);
  }
  cv::line(img, {kPlot.x, bottom}, {kPlot.x + kPlot.width, bottom}, kBlack, 1);
  cv::line(img, {kPlot.x, kPlot.y}, {kPlot.x, bottom}, kBlack, 1);
  text(img, "deviation from the reference (mm)", {kPlot.x + kPlot.width / 2, bottom + 48}, 0.55, kBlack, 0.5);
  text(img, "points", {kPlot.x, kPlot.y - 30}, 0.5, kBlack, 0.5);
}

std::string figures(const DeviationStatistics& s) {
  char line[256];
  std::snprintf(line, sizeof(line), "%zu points   mean %.4f   std %.4f   RMS %.4f   min %.4f   max %.4f mm", s.count,
                s.mean_mm, s.std_mm, s.rms_mm, s.min_mm, s.max_mm);
  return line;
}

}  // namespace

std::string deviation_histogram_png(const std::vector<double>& deviation_mm, const DeviationStatistics& s,
                                    const std::string& title) {
  std::vector<double> sorted;
  for (double d : deviation_mm) {
    if (!std::isnan(d)) sorted.push_back(d);
  }
  std::sort(sorted.begin(), sorted.end());
  cv::Mat img(kHistogramHeight, kHistogramWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  text(img, title, {kHistogramWidth / 2, 26}, 0.6, kBlack, 0.5);
  text(img, figures(s), {kHistogramWidth / 2, 48}, 0.45, kDark, 0.5);
  if (sorted.empty()) {
    text(img, "no deviations to show", {kHistogramWidth / 2, kHistogramHeight / 2}, 0.7, kDark, 0.5);
  } else {
    const std::pair<double, double> range = detail::deviation_axis(sorted, s);
    const Axis axis{range.first, range.second};
    std::vector<int> counts(kBins, 0);
    std::size_t beyond = 0;
    for (double d : sorted) {
      const double u = (d - axis.lo) / (axis.hi - axis.lo) * kBins;
      beyond += u < 0.0 || u >= kBins;
      ++counts[static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor(u)), 0, kBins - 1))];
    }
    const int max_count = *std::max_element(counts.begin(), counts.end());
    if (s.tolerance_mm) draw_band(img, axis, *s.tolerance_mm);
    const int bottom = kPlot.y + kPlot.height;
    for (int b = 0; b < kBins; ++b) {
      const double lo = axis.lo + (axis.hi - axis.lo) * b / kBins, hi = axis.lo + (axis.hi - axis.lo) * (b + 1) / kBins;
      const int top = bottom - static_cast<int>(std::lround(counts[b] / (max_count * 1.1) * kPlot.height));
      if (counts[b] > 0) {
        cv::rectangle(img, {axis.x(lo) + 1, top}, {axis.x(hi) - 1, bottom}, bgr(deviation_colour(0.5 * (lo + hi), s)),
                      cv::FILLED);
      }
    }
    cv::line(img, {axis.x(0.0), kPlot.y}, {axis.x(0.0), bottom}, kDark, 1, cv::LINE_AA);
    if (s.tolerance_mm) {
      dashed_vertical(img, axis.x(-*s.tolerance_mm), kBandLine);
      dashed_vertical(img, axis.x(*s.tolerance_mm), kBandLine);
      char line[160];
      std::snprintf(line, sizeof(line), "in tolerance %.2f %%   above %.2f %%   below %.2f %%", s.in_tolerance_pct,
                    s.above_pct, s.below_pct);
      text(img, line, {kHistogramWidth / 2, 68}, 0.45, kBandLine, 0.5);
    }
    draw_axes(img, axis, max_count);
    if (beyond > 0) {
      text(img, std::to_string(beyond) + " points beyond the axis (outliers) are counted in the end bars",
           {kPlot.x + kPlot.width, kHistogramHeight - 8}, 0.4, kDark, 1.0);
    }
  }
  return encode_png_bgr(img.ptr(), img.cols, img.rows, img.step[0]);
}

}  // namespace conform
