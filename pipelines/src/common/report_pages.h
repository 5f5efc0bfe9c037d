#pragma once
// Small builders the job reports (pipelines/*_report.cpp) share for the report core's aggregates (report/page.h).

#include <string>
#include <utility>
#include <vector>

#include "conform/report/page.h"

namespace conform::detail {

inline html::Plot line_plot(std::string title, std::string x_label, std::string y_label) {
  html::Plot p;
  p.title = std::move(title);
  p.x_label = std::move(x_label);
  p.y_label = std::move(y_label);
  return p;
}

inline html::Series series(std::string name, std::vector<double> x, std::vector<double> y, html::Rgb colour,
                           bool dots = false) {
  html::Series s;
  s.name = std::move(name);
  s.x = std::move(x);
  s.y = std::move(y);
  s.colour = colour;
  s.dots = dots;
  return s;
}

inline html::Band band(double lo, double hi, std::string label) {
  html::Band b;
  b.lo = lo;
  b.hi = hi;
  b.label = std::move(label);
  return b;
}

}  // namespace conform::detail
