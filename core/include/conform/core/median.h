#pragma once
// The median of a list of numbers, for the robust scales the jobs take from their data (spacings, residuals).

#include <algorithm>
#include <cstddef>
#include <vector>

namespace conform {

// The middle value of `values` in sorted order: for an even count the upper of the two middle ones (no averaging,
// so the result is one of the values); 0 for an empty list. Takes a copy, which it reorders.
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace conform
