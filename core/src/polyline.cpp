#include "conform/core/polyline.h"

namespace conform {

double length(const Polyline& polyline) {
  const auto& p = polyline.points;
  double total = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i) total += (p[i] - p[i - 1]).norm();
  if (polyline.closed && p.size() > 2) total += (p.front() - p.back()).norm();
  return total;
}

}  // namespace conform
