#pragma once
// Sorting many numbers in linear time: the order statistics a fit takes from all its pairs at every step (the
// residuals' trimmed share), where a comparison sort of 100k values costs more than the step's own arithmetic.

#include <vector>

namespace conform {

// Sorts `values` ascending: the same sequence as std::sort for finite values and infinities, except that -0 comes
// before +0 (std::sort leaves equal values in any order). NaNs, which std::sort cannot order, go to the ends (by
// their sign bit). A least-significant-digit radix sort on the values' bits, 8 bits a pass; a pass in which every
// value has the same digit (the exponent's high bits, as a rule) is skipped. Deterministic.
void radix_sort(std::vector<double>& values);

}  // namespace conform
