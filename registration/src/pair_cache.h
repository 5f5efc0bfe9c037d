#pragma once
// Exact reuse of each scan point's search from one ICP iteration to the next (the spatial coherence of
// correspondences between iterations that Greenspan & Godin 2001 exploit for nearest-neighbour ICP). Late iterations
// move the scan by micrometres, so almost every point skips its search; the answers are exactly the searches' own.
//   Nearest reference point: searched at `a`, nearest distance d1, second-nearest d2; now at x, |x - a| = m. The
//   triangle inequality gives |x - p1| <= d1 + m and |x - p| >= d2 - m for every other p: while 2 m < d2 - d1 the
//   nearest is still p1 (a margin covers float rounding, so no near-tie is decided here).
//   Closest surface point: searched at `a`, distance d1, keeping the triangles within d1 + 2 h (h >= d1, 1 um):
//   while |x - a| <= h, x's closest point is on one of them (TriangleIndex::closest_with_slots). Kept only once the
//   point moves little against its distance: early, big steps would leave them at once.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/core/nearest_neighbors.h"
#include "conform/core/triangle_index.h"
#include "conform/registration/icp_reference.h"

namespace conform::detail {

class PairCache {
 public:
  // Forgets every point's search and sizes the cache for `points` scan points, searched by nearest() or (surface)
  // by closest().
  void reset(std::size_t points, bool surface);
  std::size_t size() const { return anchor_.size(); }

  // The reference's point nearest to `query` (and its normal; KdTree::nearest_position) for scan point i (< size()),
  // nullptr when the reference is empty. A reused answer is read from the cache's own copy, stored in scan order:
  // late iterations read their pairs' reference data sequentially. Calls for different i may run in parallel.
  const IcpReference::Sample* nearest(const IcpReference& reference, std::size_t i, const Eigen::Vector3f& query);
  // TriangleIndex::closest(query, max_distance) for scan point i. Calls for different i may run in parallel.
  SurfacePoint closest(const TriangleIndex& surface, std::size_t i, const Eigen::Vector3d& query,
                       double max_distance);

 private:
  static constexpr std::size_t kMaxSlots = 16;  // triangles kept per point; more: search every time
  static constexpr double kNoAnchor = -2.0;      // reach_: never searched
  static constexpr double kNoSlots = -1.0;       // reach_: searched, nothing to reuse

  std::vector<Eigen::Vector3d> anchor_;  // where point i was last searched
  std::vector<double> reach_;            // how far it may move from there and keep its answer, mm; < 0: search
  std::vector<double> distance_;         // closest surface point: its distance then, mm
  std::vector<double> crowded_;          // the distance at which more than kMaxSlots triangles were in reach, mm
  std::vector<IcpReference::Sample> sample_;  // nearest point: the reference's point and normal found then
  std::vector<std::int32_t> slots_;      // closest surface point: kMaxSlots per point
  std::vector<std::uint8_t> slot_count_;
};

}  // namespace conform::detail
