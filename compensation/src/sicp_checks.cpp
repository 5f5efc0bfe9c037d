#include "conform/compensation/sicp_checks.h"

#include <algorithm>
#include <cmath>


#include "conform/compensation/sicp_blend.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::string list(const std::vector<std::size_t>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size() && i < 12; ++i) s += (i > 0 ? ", " : "") + std::to_string(v[i]);
  return v.size() > 12 ? s + ", ..." : s;
}

// Per segment: blind, bare, outlier lists and a confidence = edge-data share * residual share (1 at <= 2x noise).
void judge_segments(const SicpResult& r, const SicpCheckOptions& o, double scan_noise_mm, SicpCheck& c) {
  std::vector<double> rms;
  for (const SicpSegmentFit& f : r.segments) {
    if (f.usable && f.neighbourhood_points >= o.min_edge_points) rms.push_back(f.rms_mm);
  }
  c.noise_mm = scan_noise_mm > 0.0 ? scan_noise_mm : (rms.empty() ? r.coarse.rms_mm : median(rms));
  const double noise = std::max(c.noise_mm, 1e-6);
  for (std::size_t k = 0; k < r.segments.size(); ++k) {
    const SicpSegmentFit& f = r.segments[k];
    const bool blind = f.neighbourhood_points < o.min_edge_points;
    const bool outlier = !f.usable || f.rms_mm > o.outlier_ratio * noise;
    if (blind) c.blind_segments.push_back(k);
    if (blind && f.stability_points == 0) c.bare_segments.push_back(k);
    if (outlier && !blind) c.outlier_segments.push_back(k);
    const double needed = 2.0 * static_cast<double>(o.min_edge_points);
    const double edge = needed > 0.0 ? std::min(1.0, static_cast<double>(f.neighbourhood_points) / needed) : 1.0;
    const double fit = std::min(1.0, 2.0 * noise / std::max(f.rms_mm, 1e-9));
    c.segment_confidence.push_back(blind || outlier ? 0.0 : edge * fit);
  }
}

// The correction of row i split along the compensated row's tool axis, path direction and the cross direction.
void split_correction(const Trajectory& nominal, const Trajectory& t, std::size_t i, bool closed, SicpRowReport& row) {
  const std::size_t n = t.points.size();
  const Eigen::Vector3d d = t.points[i] - nominal.points[i];
  const Eigen::Vector3d& axis = t.normals[i];
  const std::size_t next = i + 1 < n ? i + 1 : (closed ? 0 : n - 1);
  const std::size_t previous = i > 0 ? i - 1 : (closed ? n - 1 : 0);
  Eigen::Vector3d tangent = t.points[next] - t.points[previous];
  tangent -= tangent.dot(axis) * axis;
  row.axis_mm = d.dot(axis);
  if (tangent.norm() < 1e-12) return;
  tangent.normalize();
  row.along_mm = d.dot(tangent);
  row.across_mm = d.dot(axis.cross(tangent));
}

// The warnings of blind, bare and outlier segments and far rows, each saying what to change.
void add_warnings(const SicpCheckOptions& o, std::size_t segments, SicpCheck& c) {
  if (!c.blind_segments.empty())
    c.warnings.push_back(
        std::to_string(c.blind_segments.size()) + " of " + std::to_string(segments) + " segments have fewer than " +
        std::to_string(o.min_edge_points) + " scan points near the edge (segments " + list(c.blind_segments) +
        "): their rows are guessed from the neighbours; scan the edge there (or accept guessed rows with a lower "
        "minimum of edge points)");
  if (!c.bare_segments.empty())
    c.warnings.push_back(std::to_string(c.bare_segments.size()) + " segments have no scan data at all (segments " +
                         list(c.bare_segments) + ")");
  if (!c.outlier_segments.empty())
    c.warnings.push_back(std::to_string(c.outlier_segments.size()) +
                         " segments fit the scan far worse than the others " + "(RMS above " +
                         format_fixed(o.outlier_ratio, 1) + " x the noise " + format_fixed(c.noise_mm, 4) +
                         " mm; segments " + list(c.outlier_segments) +
                         "): check the scan there (spurious points, fixtures) or the nominal surface");
  if (c.far_rows > 0)
    c.warnings.push_back(std::to_string(c.far_rows) + " trajectory rows lie more than " +
                         format_fixed(o.max_offset_mm, 1) +
                         " mm from the contour: the segments describe the part near the contour only; check that the "
                         "trajectory and the contour are in the same frame and units");
}

}  // namespace

bool SicpCheckOptions::IsValid(std::string* error) const {
  const char* why = nullptr;
  if (!std::isfinite(outlier_ratio) || outlier_ratio <= 1.0)
    why = "outlier ratio must be > 1";
  else if (!std::isfinite(max_offset_mm) || max_offset_mm <= 0.0)
    why = "largest trajectory offset from the contour must be > 0 mm";
  else if (!std::isfinite(min_confidence) || min_confidence < 0.0 || min_confidence > 1.0)
    why = "minimum row confidence must be in [0, 1]";
  if (why == nullptr) return true;
  if (error != nullptr) *error = why;
  return false;
}

SicpCheck check_sicp_path(const Polyline& contour, const SicpResult& r, const Trajectory& nominal,
                          const Trajectory& compensated, const SicpCheckOptions& o, double scan_noise_mm) {
  std::string why;
  if (!o.IsValid(&why)) throw Error("S-ICP checks: " + why);
  if (nominal.points.size() != compensated.points.size() || compensated.normals.size() != compensated.points.size())
    throw Error("S-ICP checks: the compensated trajectory's rows differ from the nominal one's");
  SicpCheck c;
  judge_segments(r, o, scan_noise_mm, c);
  const ContourSegmentation& g = r.segmentation;
  const bool by_segments = !r.segments.empty() && r.segments.size() == g.segments.size();
  const std::vector<double> s =
      by_segments ? locate_on_contour(contour, g.arc_length_mm, nominal.points) : std::vector<double>();
  const KdTree tree(contour.points);
  c.rows.resize(nominal.points.size());
  // A closed path (its ends within three median row spacings) wraps for the path direction at its ends.
  bool closed = false;
  if (nominal.points.size() >= 3) {
    std::vector<double> spacing;
    for (std::size_t i = 1; i < nominal.points.size(); ++i)
      spacing.push_back((nominal.points[i] - nominal.points[i - 1]).norm());
    closed = (nominal.points.back() - nominal.points.front()).norm() <= 3.0 * median(spacing);
  }
  c.min_confidence = 1.0;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    SicpRowReport& row = c.rows[i];
    split_correction(nominal, compensated, i, closed, row);
    float sq = 0.0f;
    tree.nearest(nominal.points[i].cast<float>(), &sq);
    row.contour_distance_mm = std::sqrt(static_cast<double>(sq));
    row.confidence = 1.0;
    if (by_segments) {
      const BlendAt b = blend_at(g, s[i]);
      row.confidence = (1.0 - b.weight) * c.segment_confidence[b.segment] + b.weight * c.segment_confidence[b.next];
    }
    if (row.contour_distance_mm > o.max_offset_mm) row.confidence = 0.0, ++c.far_rows;
    if (row.confidence < o.min_confidence) ++c.untrusted_rows;
    c.min_confidence = std::min(c.min_confidence, row.confidence);
  }
  add_warnings(o, r.segments.size(), c);
  c.trusted = r.converged && c.untrusted_rows == 0;
  if (!r.converged)
    c.reason = "the registration did not converge (" + r.termination + ")";
  else if (c.untrusted_rows > 0)
    c.reason = std::to_string(c.untrusted_rows) + " of " + std::to_string(c.rows.size()) +
               " rows have a confidence below " + format_fixed(o.min_confidence, 2) + " (" +
               (c.far_rows > 0 ? "rows far from the contour" : "segments without edge data or fitting badly") +
               "; see the warnings)";
  return c;
}

}  // namespace conform
