#include "sicp_selection.h"

#include <algorithm>
#include <cmath>

#include "conform/registration/downsample.h"

namespace conform::detail {
namespace {

// The contour point nearest arc length s (wrapped on a closed contour).
std::size_t point_at_arc(const ContourSegmentation& g, double s) {
  if (g.closed) {
    s = std::fmod(s, g.length_mm);
    if (s < 0.0) s += g.length_mm;
  }
  const auto it = std::lower_bound(g.arc_length_mm.begin(), g.arc_length_mm.end(), s);
  std::size_t i = static_cast<std::size_t>(it - g.arc_length_mm.begin());
  if (i == g.arc_length_mm.size()) return g.closed && g.length_mm - s < s - g.arc_length_mm.back() ? 0 : i - 1;
  if (i > 0 && s - g.arc_length_mm[i - 1] < g.arc_length_mm[i] - s) --i;
  return i;
}

}  // namespace

ContourLocator::ContourLocator(const Polyline& contour, const ContourSegmentation& segmentation)
    : contour_(contour), segmentation_(segmentation), tree_(contour.points) {}

std::vector<Eigen::Vector3d> ContourLocator::near_contour(const std::vector<Eigen::Vector3d>& points,
                                                          const Eigen::Isometry3d& T, double radius_mm) const {
  std::vector<Eigen::Vector3d> near;
  const double sq_radius = radius_mm * radius_mm;
  for (const Eigen::Vector3d& p : points) {
    float sq = 0.0f;
    tree_.nearest((T * p).cast<float>(), &sq);
    if (static_cast<double>(sq) <= sq_radius) near.push_back(p);
  }
  return near;
}

void ContourLocator::assign(const Eigen::Vector3d& p, int i, double d2, const SicpOptions& o,
                            std::vector<std::vector<Eigen::Vector3d>>& near,
                            std::vector<std::vector<Eigen::Vector3d>>& stable) const {
  const std::size_t count = segmentation_.segments.size();
  if (i < 0 || d2 > o.stability_mm * o.stability_mm) return;
  const double s = segmentation_.arc_length_mm[static_cast<std::size_t>(i)];
  const std::size_t core = segmentation_.core_at(s);
  // Only the core's segment and its neighbours can reach s; each is tried once (2 or fewer segments repeat).
  const std::size_t candidates[3] = {(core + count - 1) % count, core, (core + 1) % count};
  for (int c = 0; c < 3; ++c) {
    const std::size_t k = candidates[c];
    if ((c == 1 && k == candidates[0]) || (c == 2 && (k == candidates[0] || k == candidates[1]))) continue;
    if (!segmentation_.reaches(k, s)) continue;
    (d2 <= o.neighbourhood_mm * o.neighbourhood_mm ? near : stable)[k].push_back(p);
  }
}

SicpSelection ContourLocator::thin_out(std::vector<std::vector<Eigen::Vector3d>>& near,
                                       std::vector<std::vector<Eigen::Vector3d>>& stable, const SicpOptions& o) const {
  SicpSelection selection;
  for (std::size_t k = 0; k < near.size(); ++k) {
    std::vector<Eigen::Vector3d> points = stride_downsample(near[k], o.points_per_segment);
    selection.neighbourhood_counts.push_back(points.size());
    for (const Eigen::Vector3d& p : stride_downsample(stable[k], o.stability_points_per_segment)) points.push_back(p);
    selection.segment_points.push_back(std::move(points));
  }
  return selection;
}

SicpSelection ContourLocator::select_scan(const std::vector<Eigen::Vector3d>& scan,
                                          const Eigen::Isometry3d& T_nominal_scan, const SicpOptions& o) const {
  const std::size_t count = segmentation_.segments.size();
  std::vector<std::vector<Eigen::Vector3d>> near(count), stable(count);
  for (const Eigen::Vector3d& p : scan) {
    float sq = 0.0f;
    const int i = tree_.nearest((T_nominal_scan * p).cast<float>(), &sq);
    assign(p, i, static_cast<double>(sq), o, near, stable);
  }
  return thin_out(near, stable, o);
}

SicpSelection ContourLocator::reselect_scan(const std::vector<Eigen::Vector3d>& scan,
                                            const Eigen::Isometry3d& T_nominal_scan,
                                            const std::vector<Eigen::Isometry3d>& transforms,
                                            const SicpOptions& o) const {
  const std::size_t count = segmentation_.segments.size();
  std::vector<std::vector<Eigen::Vector3d>> near(count), stable(count);
  for (const Eigen::Vector3d& p : scan) {
    float sq = 0.0f;
    int i = tree_.nearest((T_nominal_scan * p).cast<float>(), &sq);
    if (i < 0) continue;
    const std::size_t k = segmentation_.core_at(segmentation_.arc_length_mm[static_cast<std::size_t>(i)]);
    i = tree_.nearest((transforms[k] * p).cast<float>(), &sq);
    assign(p, i, static_cast<double>(sq), o, near, stable);
  }
  return thin_out(near, stable, o);
}

SicpSelection ContourLocator::select_contour(const Polyline& contour, const SicpOptions& o) const {
  SicpSelection selection;
  for (std::size_t k = 0; k < segmentation_.segments.size(); ++k) {
    std::vector<Eigen::Vector3d> points;
    for (std::size_t i = 0; i < contour.points.size(); ++i) {
      if (segmentation_.reaches(k, segmentation_.arc_length_mm[i])) points.push_back(contour.points[i]);
    }
    points = stride_downsample(points, o.points_per_segment);
    selection.neighbourhood_counts.push_back(points.size());
    selection.segment_points.push_back(std::move(points));
  }
  return selection;
}

std::vector<SicpJointJunction> ContourLocator::junctions(std::size_t per_overlap) const {
  std::vector<SicpJointJunction> result;
  const std::vector<ContourSegment>& s = segmentation_.segments;
  const std::size_t count = s.size();
  const std::size_t junction_count = segmentation_.closed ? (count > 1 ? count : 0) : count - 1;
  for (std::size_t k = 0; k < junction_count; ++k) {
    SicpJointJunction j;
    j.left = k;
    j.right = (k + 1) % count;
    const double centre = s[j.right].start_mm;
    const double half = s[j.right].overlap_before_mm;
    for (std::size_t m = 0; m < per_overlap; ++m) {
      const double f =
          per_overlap == 1 ? 0.0 : -1.0 + 2.0 * static_cast<double>(m) / static_cast<double>(per_overlap - 1);
      j.points.push_back(contour_.points[point_at_arc(segmentation_, centre + f * half)]);
    }
    result.push_back(std::move(j));
  }
  return result;
}

}  // namespace conform::detail
