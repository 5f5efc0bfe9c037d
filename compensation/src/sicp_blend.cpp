#include "conform/compensation/sicp_blend.h"

#include <algorithm>
#include <cmath>

#include "conform/core/error.h"

namespace conform {

double sinusoidal_weight(double u) { return 0.5 * (1.0 - std::cos(M_PI * std::clamp(u, 0.0, 1.0))); }

BlendAt blend_at(const ContourSegmentation& g, double s) {
  const std::size_t count = g.segments.size();
  if (count == 0) throw Error("S-ICP blend: no segments");
  // The core holding s; on an open contour, points beyond the ends belong to the end segments.
  const std::size_t k = g.core_at(s);
  const ContourSegment& c = g.segments[k];
  const double d = g.ahead(c.start_mm, s);
  BlendAt b{k, k, 0.0};
  if (c.overlap_before_mm > 0.0 && d < c.overlap_before_mm) {  // second half of the overlap with the previous one
    b.segment = (k + count - 1) % count;
    b.next = k;
    b.weight = sinusoidal_weight((d + c.overlap_before_mm) / (2.0 * c.overlap_before_mm));
  } else if (c.overlap_after_mm > 0.0 && d > c.length_mm - c.overlap_after_mm) {  // first half with the next one
    b.next = (k + 1) % count;
    b.weight = sinusoidal_weight((d - (c.length_mm - c.overlap_after_mm)) / (2.0 * c.overlap_after_mm));
  }
  return b;
}

Eigen::Vector3d blend_point(const ContourSegmentation& g, const std::vector<Eigen::Isometry3d>& T, double s,
                            const Eigen::Vector3d& p) {
  const BlendAt b = blend_at(g, s);
  return (1.0 - b.weight) * (T[b.segment] * p) + b.weight * (T[b.next] * p);
}

Eigen::Vector3d blend_normal(const ContourSegmentation& g, const std::vector<Eigen::Isometry3d>& T, double s,
                             const Eigen::Vector3d& n) {
  const BlendAt b = blend_at(g, s);
  return ((1.0 - b.weight) * (T[b.segment].linear() * n) + b.weight * (T[b.next].linear() * n)).normalized();
}

}  // namespace conform
