#pragma once
// The deviation histogram's axis, shared by the PNG (deviation_histogram.cpp) and the page (deviation_view.cpp).

#include <utility>
#include <vector>

#include "conform/evaluation/statistics.h"

namespace conform::detail {

// The deviation histogram's axis [lo, hi] for ascending finite deviations: the 0.5th-99.5th percentile, but no
// further than the 2.5th (97.5th) percentile minus (plus) half the span between them, so that a few far outliers do not
// squeeze the distribution into one bar (they are counted in the end bars); then 0 and the tolerance band with a
// margin (1.3 t), padded by 5 %.
std::pair<double, double> deviation_axis(const std::vector<double>& sorted, const DeviationStatistics& statistics);

}  // namespace conform::detail
