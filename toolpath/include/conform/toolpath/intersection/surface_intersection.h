#pragma once
// The intersection curves of two Bézier networks by recursive subdivision (Simas, Dias & Guenther: the boundary of
// the damaged area; Lane & Riesenfeld style): a pair of patches whose control-point boxes overlap may intersect
// (convex-hull property), so both are split at (0.5, 0.5) and the overlapping sub-pairs recursed into, down to pieces
// smaller than the tolerance. Each surviving leaf pair gives a point, moved by Newton's method onto the exact
// intersection of the two surfaces; the points are then thinned and chained into curves, closed where the chain
// returns to its start: a crater rim. The pairs to start from come from a box tree over the second network's
// patches (O(n log n), not all pairs); the work is bounded by max_box_pairs. Each pair's boxes are taken in a frame whose z is the second patch's normal,
// which hugs a gently curved sheet far tighter than world axes.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/bezier_network.h"

namespace conform {

struct IntersectionOptions {
  double tolerance_mm = 0.05;  // subdivision stops when both pieces' box diagonals are below this, mm
  bool refine = true;          // Newton onto the exact intersection (else the leaf boxes' centres)
  int max_depth = 30;          // subdivision levels per patch, a safety net
  double link_factor = 4.0;    // neighbours on a curve: points closer than link_factor x tolerance
  std::size_t max_leaf_pairs = 2000000;  // stop (not ok) beyond this many leaf pairs: near-coincident surfaces
  std::size_t max_box_pairs = 50000000;  // stop (not ok, work_limit_hit) beyond this many box pairs examined

  bool IsValid(std::string* error) const;
};

struct IntersectionPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector2d uv_a = Eigen::Vector2d::Zero();  // parameters on the first surface
  Eigen::Vector2d uv_b = Eigen::Vector2d::Zero();  // parameters on the second surface
};

struct IntersectionCurve {
  bool closed = false;
  std::vector<IntersectionPoint> points;  // in order along the curve; a closed curve does not repeat its start
  double length_mm() const;
};

struct IntersectionResult {
  bool ok = false;
  std::string termination = "not run";
  std::vector<IntersectionCurve> curves;  // closed ones first, then by size (deterministic)
  std::size_t leaf_pairs = 0;             // box pairs that reached the tolerance
  std::size_t box_pairs = 0;              // box pairs examined (the work done)
  bool work_limit_hit = false;            // max_box_pairs reached: no curves
  std::size_t points = 0;                 // points after thinning
  std::size_t unrefined = 0;              // leaf pairs Newton found no intersection near (dropped when refining)
  double max_gap_mm = 0.0;                // max |A(uv_a) - B(uv_b)| over the points
};

// Throws conform::Error when the options are not valid.
IntersectionResult intersect_surfaces(const BezierNetwork& a, const BezierNetwork& b,
                                      const IntersectionOptions& options = {});

// The parameter polygon of a curve on the first surface contains (u, v) (even-odd rule).
bool polygon_contains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p);
std::vector<Eigen::Vector2d> parameter_polygon_a(const IntersectionCurve& curve);

}  // namespace conform
