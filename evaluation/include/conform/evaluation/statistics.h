#pragma once
// The figures a metrology report gives for a set of deviations: count, extremes, mean, standard deviation, RMS,
// percentiles, and the shares inside and outside a tolerance band +-t.
//
// Percentiles interpolate linearly between the two nearest ranks of the sorted values: the p-th percentile of n
// values x_0 <= ... <= x_(n-1) is x_k + f (x_(k+1) - x_k) with k + f = p / 100 * (n - 1) (Hyndman & Fan 1996,
// definition 7; NumPy's and Excel's PERCENTILE.INC default). The standard deviation is the population one (divide
// by n), so that rms^2 = mean^2 + std^2.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace conform {

struct DeviationStatisticsOptions {
  // The tolerance band +-t, mm (t > 0); none by default (the tolerance figures are then not computed).
  std::optional<double> tolerance_mm;

  // False (and why) when the tolerance is given but not finite and > 0.
  bool IsValid(std::string* error) const;
};

struct DeviationStatistics {
  std::size_t count = 0;     // finite values summarised
  std::size_t excluded = 0;  // NaN values left out (unmatched points)
  // Signed figures, mm; NaN when count is 0.
  double min_mm = 0.0, max_mm = 0.0;
  double mean_mm = 0.0;
  double std_mm = 0.0;  // population standard deviation about the mean
  double rms_mm = 0.0;  // sqrt(mean of squares)
  double p5_mm = 0.0, p50_mm = 0.0, p95_mm = 0.0, p99_mm = 0.0;
  double p95_abs_mm = 0.0;  // 95th percentile of |deviation|: 95 % of the points are within this distance
  double mean_abs_mm = 0.0;
  // With a tolerance t: shares of count, in percent, that sum to 100. Inside: |d| <= t (the band is closed).
  std::optional<double> tolerance_mm;
  double in_tolerance_pct = 0.0;
  double above_pct = 0.0;  // d > +t
  double below_pct = 0.0;  // d < -t

  // True when every summarised value is inside the band (and there is a band and at least one value).
  bool within_tolerance() const { return tolerance_mm.has_value() && count > 0 && in_tolerance_pct == 100.0; }
};

// The statistics of the finite values; NaN values are counted as excluded; infinite ones are an error (they are
// not deviations). Deterministic: sums are compensated and taken in order. Throws conform::Error for invalid
// options or an infinite value.
DeviationStatistics deviation_statistics(const std::vector<double>& deviation_mm,
                                         const DeviationStatisticsOptions& options = {});

// The p-th percentile (0 <= p <= 100) of ascending values by the rule above; NaN for an empty vector.
double percentile_of_sorted(const std::vector<double>& sorted, double p);

}  // namespace conform
