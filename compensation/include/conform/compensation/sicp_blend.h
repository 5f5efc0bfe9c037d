#pragma once
// Blending Subdivision-ICP's segment transforms along the contour (Béarée et al. 2010, section 3.3, with smooth
// weights): inside a junction's overlap the nominal point's image is the weighted mean of both neighbours' images,
// with the weight of the next segment rising as (1 - cos(pi u)) / 2 over the overlap (u from 0 to 1). The weights
// are exactly 0 and 1 at the overlap's ends and their slope is zero there, so the compensated path has no jump and
// no kink where one transform hands over to the next (C1).

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/registration/contour_segments.h"

namespace conform {

// (1 - cos(pi u)) / 2 for u in [0, 1]; clamped outside.
double sinusoidal_weight(double u);

// Which segments act at arc length s and how much: `weight` of `next` and 1 - weight of `segment`.
struct BlendAt {
  std::size_t segment = 0;  // the segment whose core holds s
  std::size_t next = 0;     // its neighbour in an overlap (== segment outside overlaps)
  double weight = 0.0;      // of next, in [0, 1]
};

// Throws conform::Error when the segmentation has no segments.
BlendAt blend_at(const ContourSegmentation& segmentation, double s);

// The blended image of nominal point p (at arc length s) and of its unit normal n (rotated by the blended rotation),
// with T_scan_nominal one per segment.
Eigen::Vector3d blend_point(const ContourSegmentation& segmentation,
                            const std::vector<Eigen::Isometry3d>& T_scan_nominal, double s, const Eigen::Vector3d& p);
Eigen::Vector3d blend_normal(const ContourSegmentation& segmentation,
                             const std::vector<Eigen::Isometry3d>& T_scan_nominal, double s, const Eigen::Vector3d& n);

}  // namespace conform
