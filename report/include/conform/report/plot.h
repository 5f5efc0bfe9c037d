#pragma once
// The plots of a report, drawn as inline SVG by render_html (docs/report.md): bars (a histogram) or lines (y against
// x, several series), with an optional shaded band across x (e.g. the tolerance +-t) or across y, and marker lines.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "conform/report/scene.h"

namespace conform::html {

// A tick step of 1, 2 or 5 times a power of ten giving about `count` intervals over `span` (> 0).
double nice_step(double span, int count);

struct Series {
  std::string name;  // the legend's label
  std::vector<double> x;
  std::vector<double> y;  // as many as x; NaN breaks the line
  Rgb colour = kBlue;
  bool dots = false;  // a dot at every point too
};

struct Bar {
  double lo = 0.0;  // the bin [lo, hi)
  double hi = 0.0;
  double count = 0.0;
  Rgb colour = kBlue;
};

struct Band {
  double lo = 0.0;
  double hi = 0.0;
  std::string label;  // "tolerance +-0.1 mm"
  bool reject = false;  // shaded red (values here are not acceptable), else green (the acceptable range)
};

struct Plot {
  std::string title;
  std::string x_label;  // with the unit: "deviation (mm)"
  std::string y_label;
  std::vector<Bar> bars;        // a histogram, or
  std::vector<Series> series;   // lines
  std::optional<Band> x_band;   // shaded between x = lo and hi
  std::optional<Band> y_band;   // shaded between y = lo and hi
  std::vector<double> x_marks;  // vertical lines (e.g. x = 0)
  std::string note;             // one line under the plot ("12 points beyond the axis are in the end bars")
  // A histogram's values beyond its axis, counted in the first (below) and last (above) bar; those bars are marked
  // and labelled on the plot ("81 below -0.31").
  std::size_t below = 0;
  std::size_t above = 0;
};

// A histogram of the finite `values` in `bins` (>= 1) equal bins over [lo, hi] (values outside go into the end bins,
// counted in below / above, and the note says how many); each bar coloured by `colour` of its centre (empty: kBlue).
// lo < hi.
Plot histogram_plot(const std::vector<double>& values, std::size_t bins, double lo, double hi, std::string title,
                    std::string x_label, const std::function<Rgb(double)>& colour = {});

}  // namespace conform::html
