#pragma once
// The histogram of `conform compare --out-histogram`, drawn with OpenCV: deviation (mm) across, points up, bars in
// the deviation map's colours, zero marked, the tolerance band shaded and its limits labelled, the figures on top.
// The axis spans the 0.5th to 99.5th percentile (and 0, and the band with a margin); the few values beyond go
// into the end bars, and a note says how many.

#include <string>
#include <vector>

#include "conform/evaluation/statistics.h"

namespace conform {

// PNG bytes (960 x 560 pixels, 8-bit colour). NaN values (unmatched points) are left out.
std::string deviation_histogram_png(const std::vector<double>& deviation_mm, const DeviationStatistics& statistics,
                                    const std::string& title);

inline constexpr int kHistogramWidth = 960;
inline constexpr int kHistogramHeight = 560;

}  // namespace conform
