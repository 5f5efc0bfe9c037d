#pragma once
// Which points take part in which Subdivision-ICP segment: every point is located on the contour by its nearest
// contour point (its arc length) and its distance from the contour, and joins each segment that reaches that arc
// length: as a neighbourhood point within neighbourhood_mm, as a stability point up to stability_mm.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/nearest_neighbors.h"
#include "conform/core/polyline.h"
#include "conform/registration/contour_segments.h"
#include "conform/registration/sicp.h"

namespace conform::detail {

struct SicpSelection {
  std::vector<std::vector<Eigen::Vector3d>> segment_points;  // per segment: neighbourhood points, then stability
  std::vector<std::size_t> neighbourhood_counts;
};

class ContourLocator {
 public:
  ContourLocator(const Polyline& contour, const ContourSegmentation& segmentation);

  // The points p with T p within radius_mm of the contour.
  std::vector<Eigen::Vector3d> near_contour(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                                            double radius_mm) const;
  // Scan points (scan frame) per segment, located at T_nominal_scan.
  SicpSelection select_scan(const std::vector<Eigen::Vector3d>& scan, const Eigen::Isometry3d& T_nominal_scan,
                            const SicpOptions& options) const;
  // Scan points per segment again, each point located at the transform of the segment it falls in at
  // T_nominal_scan (transforms: one T_nominal_scan per segment): where the part bends far from the rigid pose, the
  // segments' own poses find the edge's points that the rigid pose put beyond the neighbourhood.
  SicpSelection reselect_scan(const std::vector<Eigen::Vector3d>& scan, const Eigen::Isometry3d& T_nominal_scan,
                              const std::vector<Eigen::Isometry3d>& transforms, const SicpOptions& options) const;
  // Contour points per segment (the contour-only variant).
  SicpSelection select_contour(const Polyline& contour, const SicpOptions& options) const;
  // Shared points of neighbouring segments: `per_overlap` contour points evenly over each junction's overlap.
  std::vector<SicpJointJunction> junctions(std::size_t per_overlap) const;

 private:
  const Polyline& contour_;
  const ContourSegmentation& segmentation_;
  KdTree tree_;
  // Distributes p (its nearest contour point i at squared distance d2) to the segments that reach i's arc length.
  void assign(const Eigen::Vector3d& p, int i, double d2, const SicpOptions& o,
              std::vector<std::vector<Eigen::Vector3d>>& near, std::vector<std::vector<Eigen::Vector3d>>& stable) const;
  SicpSelection thin_out(std::vector<std::vector<Eigen::Vector3d>>& near,
                         std::vector<std::vector<Eigen::Vector3d>>& stable, const SicpOptions& o) const;
};

}  // namespace conform::detail
