#pragma once
// How rank_starts (multi_start.h) scores a pose of the scan's probe points against the reference, and tells two
// poses apart: the inlier share (MultiStartOptions::inlier_distance_mm), the truncated RMS that breaks its ties, and
// the one-sided counts of two poses' inlier sets with the chance test on them.

#include <cstddef>
#include <vector>

#include <Eigen/Geometry>

#include "conform/registration/icp_reference.h"
#include "conform/registration/multi_start.h"

namespace conform::detail {

// sqrt(mean(min(d, cap)^2)) over the points moved by T, d the distance to the nearest reference point (mm).
double truncated_rms(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                     const IcpReference& reference, double cap);

// Which points (moved by T) lie within `tolerance` of the reference plane at their nearest reference point, that
// point no farther than `reach` (a mesh's vertices are sparse: the plane distance is the one that measures the fit).
std::vector<char> inliers(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                          const IcpReference& reference, double tolerance, double reach);

// The share of a mask's entries that are set (mask not empty).
double share_of(const std::vector<char>& mask);

// The points inlying at the best's pose only and at the other's only (two inlier masks of the same points).
struct OneSided {
  std::size_t best_only = 0;
  std::size_t other_only = 0;
};
OneSided one_sided(const std::vector<char>& best, const std::vector<char>& other);

// Whether the best start's inliers outnumber the other's where they disagree, beyond chance: at two poses of a
// symmetric surface the points in only one pose's inlier set are threshold noise, equally likely either way
// (binomial, p = 1/2); a real difference (a boss that only one pose puts on the reference) is one-sided. n: the
// points counted; o: separation_min_share, separation_ratio, separation_z.
bool separated(std::size_t best_only, std::size_t other_only, std::size_t n, const MultiStartOptions& o);

// Higher share first, then lower truncated RMS.
bool better(const StartReport& a, const StartReport& b);

// The diagonal of the points' bounding box, mm.
double size_of(const std::vector<Eigen::Vector3d>& points);

}  // namespace conform::detail
