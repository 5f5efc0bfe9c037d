#pragma once
// The deviation map's colour scale (`conform compare --out-deviation`): diverging, centred on 0, the convention of
// metrology reports. With a tolerance t: green inside the band (|d| <= t), from yellow to red above it, from cyan to
// blue below it. Without one: a continuous blue - cyan - green - yellow - red ramp over [-R, R]. The ramps span up
// to R = max(2 t, 3 RMS), but not beyond the largest |deviation|; larger values take the end colour. Unmatched
// points (NaN) are grey.

#include <array>
#include <cstdint>
#include <optional>

#include "conform/evaluation/statistics.h"

namespace conform {

using Rgb = std::array<std::uint8_t, 3>;

// R of the scale above, mm (> 0).
double colour_scale_range_mm(const DeviationStatistics& statistics);
Rgb deviation_colour(double deviation_mm, const DeviationStatistics& statistics);

}  // namespace conform
