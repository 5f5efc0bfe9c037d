#pragma once
// Reference surface inside a scan's footprint that no scan point lies on (rank_starts, multi_start.h): at two poses
// that fit the scan almost as well, the scan's holes (a pin hole, a notch, a slot the part really has) lie over
// reference holes at the right one and over solid reference surface at a wrong one. The scan-side inlier test does
// not see that: every scan point finds surface at both poses.

#include <cstddef>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/nearest_neighbors.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {

class ScanFootprint {
 public:
  // At most max_points of the scan, evenly strided, in the scan's frame; its spacing the square root of its area per
  // point (area_per_point: a random sample's median neighbour distance is half that, a grid's 1.1 times). Throws
  // conform::Error for fewer than 9 points.
  ScanFootprint(const std::vector<Eigen::Vector3d>& scan, std::size_t max_points);

  // The reference points (reference frame) that the scan moved by T_ref_scan should have covered and did not: no scan
  // point within 2.5 spacings, yet scan points on the point's tangent plane (within sheet_mm, plus a tenth of the
  // distance for curvature) and facing its way (normals within 45 deg) found along each of 8 directions round it
  // within 80 spacings. Such a point is surrounded by the scanned surface it lies on (a hole in the scan over
  // reference surface), not beyond the scan's rim or on a face the scanner did not face (whose bounding edges, on
  // its plane, belong to faces across it). Each flagged point's position in the scan's frame. Regions are found from
  // seeds (the reference points within 4 spacings of the scan's rim points: a gap's nearest scan point lies on the rim
  // of the empty region round it) and grown through reference points within link_mm of each other.
  // reference_area_mm2: the reference's area per point (area_per_point), which thins the seeds of a reference denser
  // than the scan.
  std::vector<Eigen::Vector3d> gaps(const IcpReference& reference, const Eigen::Isometry3d& T_ref_scan,
                                    double sheet_mm, double link_mm, double reference_area_mm2) const;

  double spacing_mm() const { return spacing_mm_; }
  const Eigen::AlignedBox3d& box() const { return box_; }

 private:
  // Whether a scan point near the plane through q with normal n is found marching from q along u (unit, in the
  // plane) up to `to`.
  bool hits(const Eigen::Vector3d& q, const Eigen::Vector3d& n, const Eigen::Vector3d& u, double to,
            double sheet_mm) const;

  std::vector<Eigen::Vector3d> points_;
  KdTree tree_;
  double spacing_mm_ = 0.0;
  Eigen::AlignedBox3d box_;
  std::vector<std::size_t> rim_;  // the points on the scan's rims, outer or round a hole
  std::vector<Eigen::Vector3d> normals_;  // each point's unoriented normal (its kRimNeighbours' scatter)
};

// The reference surface's area per point (mm^2): pi r^2 / 8 at the median distance r to a point's 8th neighbour,
// over up to 500 points evenly strided. 0 for fewer than 9 points.
double area_per_point(const std::vector<Eigen::Vector3d>& points, const KdTree& tree);

// The points of `gaps` farther than `apart_mm` from every point of `others` (all in the scan's frame), grouped into
// regions of points within link_mm of each other: the number of points in the largest such region.
std::size_t largest_gap_only_here(const std::vector<Eigen::Vector3d>& gaps, const std::vector<Eigen::Vector3d>& others,
                                  double apart_mm, double link_mm);

// The scan's holes compared at two poses (rank_starts): the footprint built on first use, each pose's gaps found once.
// Not thread-safe.
class GapComparison {
 public:
  // `scan` and `reference` must outlive this; the footprint holds at most scan_points of the scan; a scanned surface
  // lies within sheet_mm of its tangent plane (a few noise widths).
  GapComparison(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference, std::size_t scan_points,
                double sheet_mm);

  // The largest region of gaps (reference points) at T_a only and at T_b only: gaps at one pose with none at the same
  // place of the scan at the other (within two spacings, the coarser of scan and reference, each the square root of
  // its area per point: regions of a random sample linked at that stay whole).
  struct Regions {
    std::size_t a_only = 0;
    std::size_t b_only = 0;
  };
  // A pose that moves no corner of the scan's bounding box more than half a scan spacing from one already seen reuses
  // that one's gaps (the starts that converge on one pose end a few microns apart).
  Regions compare(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b);

  double area_per_point_mm2() const { return area_per_point_; }
  // The scan footprint's spacing (ScanFootprint::spacing_mm); builds it on the first call.
  double scan_spacing_mm();

 private:
  const std::vector<Eigen::Vector3d>& gaps(const Eigen::Isometry3d& T);

  const std::vector<Eigen::Vector3d>& scan_;
  const IcpReference& reference_;
  std::size_t scan_points_;
  double sheet_mm_;
  double area_per_point_;
  double link_mm_ = 0.0;
  std::optional<ScanFootprint> footprint_;
  std::deque<std::pair<Eigen::Isometry3d, std::vector<Eigen::Vector3d>>> found_;  // a deque: references stay valid
};

}  // namespace conform::detail
