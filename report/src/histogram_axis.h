#pragma once
// Axis helpers shared by the PNG histogram (deviation_histogram.cpp) and the page's SVG plots (not public API).

#include <utility>
#include <vector>

#include "conform/evaluation/statistics.h"

namespace conform::detail {

// A step of 1, 2 or 5 times a power of ten giving about `count` intervals over `span` (> 0).
double nice_step(double span, int count);

// The deviation histogram's axis [lo, hi] for ascending finite deviations: the 0.5th-99.5th percentile, 0 and the
// tolerance band with a margin (1.3 t), padded by 5 %.
std::pair<double, double> deviation_axis(const std::vector<double>& sorted, const DeviationStatistics& statistics);

}  // namespace conform::detail
