#include "conform/report/plot.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace conform::html {

double nice_step(double span, int count) {
  const double raw = span / count;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * power >= raw) return m * power;
  }
  return 10.0 * power;
}

Plot histogram_plot(const std::vector<double>& values, std::size_t bins, double lo, double hi, std::string title,
                    std::string x_label, const std::function<Rgb(double)>& colour) {
  if (bins == 0 || !(lo < hi)) throw std::invalid_argument("histogram_plot: needs bins >= 1 and lo < hi");
  Plot plot;
  plot.title = std::move(title);
  plot.x_label = std::move(x_label);
  plot.y_label = "count";
  std::vector<double> counts(bins, 0.0);
  const double width = (hi - lo) / static_cast<double>(bins);
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    const double u = std::floor((v - lo) / width);
    plot.below += u < 0.0;
    plot.above += u >= static_cast<double>(bins);
    counts[static_cast<std::size_t>(std::clamp(u, 0.0, static_cast<double>(bins - 1)))] += 1.0;
  }
  for (std::size_t b = 0; b < bins; ++b) {
    const double a = lo + width * static_cast<double>(b), z = lo + width * static_cast<double>(b + 1);
    plot.bars.push_back({a, z, counts[b], colour ? colour(0.5 * (a + z)) : kBlue});
  }
  if (plot.below + plot.above > 0) {
    plot.note = std::to_string(plot.below + plot.above) + " values beyond the axis are counted in the end bars";
  }
  return plot;
}

}  // namespace conform::html
