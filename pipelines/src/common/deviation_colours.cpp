#include "conform/pipelines/common/deviation_colours.h"

#include <algorithm>
#include <cmath>

namespace conform {
namespace {

struct Stop {
  double at;
  double r, g, b;
};

// Linear between the stops (ascending `at`), clamped at both ends.
template <std::size_t N>
Rgb ramp(const Stop (&stops)[N], double u) {
  u = std::clamp(u, stops[0].at, stops[N - 1].at);
  std::size_t k = 0;
  while (k + 2 < N && u > stops[k + 1].at) ++k;
  const Stop& a = stops[k];
  const Stop& b = stops[k + 1];
  const double f = (u - a.at) / (b.at - a.at);
  const auto mix = [f](double x, double y) { return static_cast<std::uint8_t>(std::lround(x + f * (y - x))); };
  return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

constexpr Rgb kGreen = {0, 190, 60};
constexpr Rgb kGrey = {128, 128, 128};
constexpr Stop kContinuous[] = {
    {-1.0, 0, 0, 255}, {-0.5, 0, 230, 255}, {0.0, 0, 190, 60}, {0.5, 255, 230, 0}, {1.0, 255, 0, 0}};
constexpr Stop kAbove[] = {{0.0, 255, 230, 0}, {0.5, 255, 130, 0}, {1.0, 220, 0, 0}};
constexpr Stop kBelow[] = {{0.0, 0, 230, 255}, {0.5, 0, 120, 255}, {1.0, 0, 0, 220}};

}  // namespace

double colour_scale_range_mm(const DeviationStatistics& s) {
  const double t = s.tolerance_mm.value_or(0.0);
  const double largest = s.count > 0 ? std::max(std::abs(s.min_mm), std::abs(s.max_mm)) : 0.0;
  double range = std::min(3.0 * (s.count > 0 ? s.rms_mm : 0.0), largest);
  range = std::max(range, 2.0 * t);
  return range > 0.0 ? range : 1e-3;  // all deviations zero: any range shows them green
}

Rgb deviation_colour(double d, const DeviationStatistics& s) {
  if (std::isnan(d)) return kGrey;
  const double range = colour_scale_range_mm(s);
  if (!s.tolerance_mm) return ramp(kContinuous, d / range);
  const double t = *s.tolerance_mm;
  if (std::abs(d) <= t) return kGreen;
  const double u = (std::abs(d) - t) / (range - t);  // range >= 2t > t
  return d > 0.0 ? ramp(kAbove, u) : ramp(kBelow, u);
}

}  // namespace conform
