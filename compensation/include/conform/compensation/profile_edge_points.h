#pragma once
// The measured edge points of a deformed profile, checked before any fit (Chen et al., LNG profiles): a laser profile
// sensor walks along the edge, so the points come in measuring order, start at the profile's origin (Ty = 0) and are
// spaced by the sensor's step, with an occasional dropout. A point out of order (by more than the noise explains) or a
// hole in the scan would silently bend the edge curve; both are refused here with the index and the coordinates of the
// offending point. Points out of order within the noise (a dense, noisy scan) are sorted along the main axis, and
// exact repeats dropped.

#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct ProfileEdgePointsOptions {
  double max_gap_mm = 50.0;  // largest allowed distance between consecutive points, mm (> 0)
  int min_points = 4;        // a cubic has 4 coefficients per coordinate: fewer points cannot determine it (>= 4)
  double order_tolerance_sigma = 6.0;  // a step back along the axis up to this many sigma sqrt(2) is noise (>= 0)

  bool IsValid(std::string* error) const;
};

struct ProfileEdgePointsCheck {
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // the main direction of the points, from the first to the last
  double chord_length_mm = 0.0;                     // sum of the distances between consecutive points
  double median_spacing_mm = 0.0;
  double max_gap_mm = 0.0;  // the largest distance between consecutive points
  int max_gap_index = 0;    // the point (0-based) that ends that gap
  double noise_mm = 0.0;    // per-coordinate noise estimated from second differences (robust, median based)
  double order_tolerance_mm = 0.0;  // the step back along the axis accepted as noise
  std::size_t reordered = 0;        // points that lie (within the tolerance) behind the one before them
  std::size_t duplicates = 0;       // exact repeats of a point, dropped
  std::vector<int> order;           // input indices of the points kept, sorted along the axis
  std::vector<double> along_mm;     // their projections on the axis, from the first input point, mm
};

// Checks and describes the points. `source` names them in messages (a file name); noise_mm > 0 replaces the estimate
// for the order tolerance. Throws conform::Error when the options are invalid, there are fewer than min_points
// (distinct) points, a coordinate is not finite, a point lies further back along the main axis than the order
// tolerance from the furthest point before it (not in measuring order), or two points next to each other along the
// axis are further apart than max_gap_mm; the message gives the point's index (0-based) and coordinates.
ProfileEdgePointsCheck check_profile_edge_points(const std::vector<Eigen::Vector3d>& points,
                                                 const ProfileEdgePointsOptions& options,
                                                 const std::string& source = "edge points", double noise_mm = 0.0);

// sigma per coordinate from each point against the chord of its two neighbours, taken at the point's own place along
// the main axis (so that uneven steps, dropouts, cancel): across the axis that difference has variance
// (1 + w^2 + (1 - w)^2) sigma^2 per component, w the point's fraction of the way, so the scaled squared difference is
// sigma^2 times a chi-square with 2 degrees of freedom (median 2 ln 2); the median ignores the few triples that hold
// an outlier. Zero for fewer than 3 points.
double estimate_edge_noise_mm(const std::vector<Eigen::Vector3d>& points);

}  // namespace conform
