#include "conform/registration/contour_segments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>  // cross(): defined there (it used to link only through PCL's sample_consensus)

#include "conform/core/csv.h"
#include "conform/core/error.h"

namespace conform {
namespace {

bool fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
  return false;
}

// Position at arc length s along the contour (wrapped on a closed one, clamped to the ends of an open one).
Eigen::Vector3d point_at(const Polyline& c, const std::vector<double>& s_of, double length, double s) {
  const std::size_t n = c.points.size();
  if (c.closed) {
    s = std::fmod(s, length);
    if (s < 0.0) s += length;
  } else {
    s = std::clamp(s, 0.0, length);
  }
  const auto it = std::upper_bound(s_of.begin(), s_of.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - s_of.begin()) - 1;  // s_of[0] = 0 <= s
  if (i + 1 >= n && !c.closed) return c.points.back();
  const Eigen::Vector3d& a = c.points[i];
  const Eigen::Vector3d& b = c.points[(i + 1) % n];
  const double end = i + 1 < n ? s_of[i + 1] : length;
  const double f = end > s_of[i] ? (s - s_of[i]) / (end - s_of[i]) : 0.0;
  return a + f * (b - a);
}

double circumradius(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double twice_area = (b - a).cross(c - a).norm();
  const double product = (b - a).norm() * (c - b).norm() * (a - c).norm();
  if (twice_area <= 1e-12 * product || product == 0.0) return std::numeric_limits<double>::infinity();
  return product / (2.0 * twice_area);
}

// The point of smallest radius in every run of consecutive points below the threshold (wrapping on a closed contour).
std::vector<int> find_corners(const std::vector<double>& radius, double threshold, bool closed) {
  const int n = static_cast<int>(radius.size());
  std::vector<int> corners;
  if (threshold <= 0.0) return corners;
  int start = 0;
  if (closed) {  // start the scan at a point above the threshold, so that no run is cut in two
    while (start < n && radius[static_cast<std::size_t>(start)] < threshold) ++start;
    if (start == n) return corners;  // a curve tighter than the threshold everywhere has no distinct corner
  }
  int best = -1;
  for (int k = 0; k <= n; ++k) {
    const int i = closed ? (start + k) % n : k;
    const bool below = k < n && radius[static_cast<std::size_t>(i)] < threshold;
    if (below && (best < 0 || radius[static_cast<std::size_t>(i)] < radius[static_cast<std::size_t>(best)])) best = i;
    if (!below && best >= 0) {
      corners.push_back(best);
      best = -1;
    }
  }
  std::sort(corners.begin(), corners.end());
  return corners;
}

// Pieces between subdivision points, each cut into ceil(length / epsilon) equal segments (Eq. (6) of the paper).
std::vector<ContourSegment> cut(const std::vector<double>& breaks, double length, bool closed,
                                const ContourSegmentationOptions& o, const std::vector<bool>& at_corner) {
  std::vector<ContourSegment> segments;
  const std::size_t pieces = closed ? breaks.size() : breaks.size() - 1;
  for (std::size_t p = 0; p < pieces; ++p) {
    const double a = breaks[p];
    const double b = p + 1 < breaks.size() ? breaks[p + 1] : breaks[0] + length;
    const int n = std::max(1, static_cast<int>(std::ceil((b - a) / o.segment_length_mm - 1e-9)));
    for (int k = 0; k < n; ++k) {
      ContourSegment s;
      s.start_mm = std::fmod(a + (b - a) * k / n, length);
      s.length_mm = (b - a) / n;
      s.starts_at_corner = k == 0 && at_corner[p];
      s.ends_at_corner = k == n - 1 && at_corner[(p + 1) % breaks.size()];
      segments.push_back(s);
    }
  }
  const std::size_t count = segments.size();
  const std::size_t junctions = closed ? count : count - 1;
  for (std::size_t k = 0; k < junctions; ++k) {
    ContourSegment& left = segments[k];
    ContourSegment& right = segments[(k + 1) % count];
    const double half = 0.5 * o.overlap * std::min(left.length_mm, right.length_mm);
    left.overlap_after_mm = half;
    right.overlap_before_mm = half;
  }
  return segments;
}

}  // namespace

bool ContourSegmentationOptions::IsValid(std::string* error) const {
  if (!std::isfinite(segment_length_mm) || segment_length_mm < 1.0 || segment_length_mm > 1e5)
    return fail(error, "segment length must be in [1, 1e5] mm (a segment shorter than a millimetre holds no scan)");
  if (max_segments < 1) return fail(error, "the segment limit must be >= 1");
  if (!std::isfinite(overlap) || overlap <= 0.0 || overlap >= 1.0)
    return fail(error, "overlap must be in (0, 1) (a share of the shorter segment at each junction)");
  if (!std::isfinite(curvature_radius_mm) || curvature_radius_mm < 0.0)
    return fail(error, "curvature radius must be >= 0 mm (0: no corner detection)");
  if (!std::isfinite(curvature_window_mm) || curvature_window_mm <= 0.0)
    return fail(error, "curvature window must be > 0 mm");
  return true;
}

double ContourSegmentation::ahead(double from, double s) const {
  if (!closed) return s - from;
  double d = std::fmod(s - from, length_mm);
  if (d < 0.0) d += length_mm;
  return d;
}

std::size_t ContourSegmentation::core_at(double s) const {
  const std::size_t count = segments.size();
  if (count <= 1) return 0;
  if (closed) {
    s = std::fmod(s - segments.front().start_mm, length_mm);
    if (s < 0.0) s += length_mm;
    s += segments.front().start_mm;
  }
  // The last segment whose start is at or before s; the cores tile the contour in order from the first start.
  std::size_t lo = 0, hi = count;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    const double start = segments[mid].start_mm < segments.front().start_mm ? segments[mid].start_mm + length_mm
                                                                            : segments[mid].start_mm;
    (start <= s ? lo : hi) = mid;
  }
  return lo;
}

bool ContourSegmentation::reaches(std::size_t k, double s) const {
  const ContourSegment& g = segments[k];
  const double from = g.start_mm - g.overlap_before_mm;
  const double d = ahead(from, s);
  return d >= 0.0 && d <= g.overlap_before_mm + g.length_mm + g.overlap_after_mm;
}

std::vector<double> arc_lengths(const Polyline& contour) {
  std::vector<double> s(contour.points.size(), 0.0);
  for (std::size_t i = 1; i < s.size(); ++i) s[i] = s[i - 1] + (contour.points[i] - contour.points[i - 1]).norm();
  return s;
}

std::vector<double> osculating_radii(const Polyline& contour, double window_mm) {
  const std::vector<double> s = arc_lengths(contour);
  const double length = conform::length(contour);
  std::vector<double> radius(contour.points.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    radius[i] = circumradius(point_at(contour, s, length, s[i] - window_mm), contour.points[i],
                             point_at(contour, s, length, s[i] + window_mm));
  }
  return radius;
}

ContourSegmentation segment_contour(const Polyline& contour, const ContourSegmentationOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("contour segmentation: " + why);
  if (contour.points.size() < 3) throw Error("contour: fewer than 3 points");
  for (std::size_t i = 0; i < contour.points.size(); ++i) {
    if (!contour.points[i].allFinite()) throw Error("contour: point " + std::to_string(i) + " is not finite");
  }
  ContourSegmentation r;
  r.closed = contour.closed;
  r.length_mm = length(contour);
  if (!(r.length_mm > 0.0)) throw Error("contour: zero length (all points coincide)");
  r.arc_length_mm = arc_lengths(contour);
  r.radius_mm = osculating_radii(contour, options.curvature_window_mm);
  r.corners = find_corners(r.radius_mm, options.curvature_radius_mm, contour.closed);
  std::vector<double> breaks;
  std::vector<bool> at_corner;
  if (!r.closed || r.corners.empty()) {
    breaks.push_back(0.0);
    at_corner.push_back(false);
  }
  for (int c : r.corners) {
    const double s = r.arc_length_mm[static_cast<std::size_t>(c)];
    if (!r.closed && (s <= 0.0 || s >= r.length_mm)) continue;  // an open contour's ends are breaks already
    breaks.push_back(s);
    at_corner.push_back(true);
  }
  if (!r.closed) {
    breaks.push_back(r.length_mm);
    at_corner.push_back(false);
  }
  // Eq. (6) per piece: at most L / epsilon + one per piece. Checked before the segments (and their ICPs) exist.
  const double estimate = r.length_mm / options.segment_length_mm + static_cast<double>(breaks.size());
  if (estimate > static_cast<double>(options.max_segments)) {
    throw Error("contour segmentation: a contour of " + format_fixed(r.length_mm, 1) + " mm in segments of at most " +
                format_fixed(options.segment_length_mm, 1) + " mm needs about " +
                std::to_string(std::llround(estimate)) + " segments, more than the limit of " +
                std::to_string(options.max_segments) +
                " (max_segments): check the contour's units and points, or give a longer segment length");
  }
  r.segments = cut(breaks, r.length_mm, r.closed, options, at_corner);
  return r;
}

}  // namespace conform
