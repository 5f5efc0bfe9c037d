#include "conform/evaluation/statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {

bool DeviationStatisticsOptions::IsValid(std::string* error) const {
  if (!tolerance_mm || (std::isfinite(*tolerance_mm) && *tolerance_mm > 0.0)) return true;
  if (error != nullptr) *error = "the tolerance must be > 0 mm, not " + std::to_string(*tolerance_mm);
  return false;
}

namespace {


// Neumaier's compensated sum: the mean of a million deviations keeps its last digits, and the order is fixed.
class Sum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    compensation_ += std::abs(sum_) >= std::abs(x) ? (sum_ - t) + x : (x - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

void set_empty(DeviationStatistics& s) {
  for (double* v : {&s.min_mm, &s.max_mm, &s.mean_mm, &s.std_mm, &s.rms_mm, &s.p5_mm, &s.p50_mm, &s.p95_mm, &s.p99_mm,
                    &s.p95_abs_mm, &s.mean_abs_mm, &s.in_tolerance_pct, &s.above_pct, &s.below_pct}) {
    *v = kNaN;
  }
}

void moments(const std::vector<double>& values, DeviationStatistics& s) {
  const auto n = static_cast<double>(values.size());
  Sum sum, sum_abs, sum_sq;
  for (double d : values) {
    sum.add(d);
    sum_abs.add(std::abs(d));
    sum_sq.add(d * d);
  }
  s.mean_mm = sum.value() / n;
  s.mean_abs_mm = sum_abs.value() / n;
  s.rms_mm = std::sqrt(sum_sq.value() / n);
  // Two passes (about the mean) rather than E[d^2] - mean^2, which cancels when the spread is small.
  Sum spread;
  for (double d : values) spread.add((d - s.mean_mm) * (d - s.mean_mm));
  s.std_mm = std::sqrt(spread.value() / n);
}

void tolerance_shares(const std::vector<double>& values, double t, DeviationStatistics& s) {
  std::size_t above = 0, below = 0;
  for (double d : values) {
    if (d > t) ++above;
    if (d < -t) ++below;
  }
  const auto n = static_cast<double>(values.size());
  const std::size_t inside = values.size() - above - below;
  s.in_tolerance_pct = 100.0 * static_cast<double>(inside) / n;
  s.above_pct = 100.0 * static_cast<double>(above) / n;
  s.below_pct = 100.0 * static_cast<double>(below) / n;
}

}  // namespace

double percentile_of_sorted(const std::vector<double>& sorted, double p) {
  if (!(p >= 0.0 && p <= 100.0)) throw Error("percentile " + std::to_string(p) + " is not in [0, 100]");
  if (sorted.empty()) return kNaN;
  // Hyndman & Fan (1996) definition 7: rank h = p (n - 1), linear between x_floor(h) and x_floor(h)+1.
  const double rank = p / 100.0 * static_cast<double>(sorted.size() - 1);
  const auto k = static_cast<std::size_t>(std::floor(rank));
  if (k + 1 >= sorted.size()) return sorted.back();
  const double f = rank - static_cast<double>(k);
  return f == 0.0 ? sorted[k] : sorted[k] + f * (sorted[k + 1] - sorted[k]);
}

DeviationStatistics deviation_statistics(const std::vector<double>& deviation_mm,
                                         const DeviationStatisticsOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("deviation statistics: " + why);
  std::vector<double> values;
  values.reserve(deviation_mm.size());
  DeviationStatistics s;
  s.tolerance_mm = options.tolerance_mm;
  for (std::size_t i = 0; i < deviation_mm.size(); ++i) {
    const double d = deviation_mm[i];
    if (std::isnan(d)) {
      ++s.excluded;
    } else if (std::isinf(d)) {
      throw Error("deviation statistics: value " + std::to_string(i) + " is infinite");
    } else {
      values.push_back(d);
    }
  }
  s.count = values.size();
  if (values.empty()) {
    set_empty(s);
    return s;
  }
  moments(values, s);
  if (options.tolerance_mm) tolerance_shares(values, *options.tolerance_mm, s);
  std::sort(values.begin(), values.end());
  s.min_mm = values.front();
  s.max_mm = values.back();
  s.p5_mm = percentile_of_sorted(values, 5.0);
  s.p50_mm = percentile_of_sorted(values, 50.0);
  s.p95_mm = percentile_of_sorted(values, 95.0);
  s.p99_mm = percentile_of_sorted(values, 99.0);
  for (double& d : values) d = std::abs(d);
  std::sort(values.begin(), values.end());
  s.p95_abs_mm = percentile_of_sorted(values, 95.0);
  return s;
}

}  // namespace conform
