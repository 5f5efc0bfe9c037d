#include "pair_cache.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conform::detail {

void PairCache::reset(std::size_t points, bool surface) {
  anchor_.assign(points, Eigen::Vector3d::Zero());
  reach_.assign(points, kNoAnchor);
  distance_.assign(surface ? points : 0, std::numeric_limits<double>::infinity());
  crowded_.assign(surface ? points : 0, std::numeric_limits<double>::infinity());
  sample_.assign(surface ? 0 : points, IcpReference::Sample{});
  slots_.assign(surface ? points * kMaxSlots : 0, 0);
  slot_count_.assign(surface ? points : 0, 0);
}

const IcpReference::Sample* PairCache::nearest(const IcpReference& reference, std::size_t i,
                                               const Eigen::Vector3f& query) {
  const Eigen::Vector3d q = query.cast<double>();
  if (reach_[i] >= 0.0 && (q - anchor_[i]).norm() < reach_[i]) return &sample_[i];
  thread_local std::vector<int> positions;
  thread_local std::vector<float> sq_distances;
  reference.tree().knn_positions(query, 2, positions, sq_distances);
  if (positions.empty()) return nullptr;
  anchor_[i] = q;
  sample_[i] = reference.by_position()[static_cast<std::size_t>(positions[0])];
  reach_[i] = kNoSlots;
  if (positions.size() == 2) {
    const double d1 = std::sqrt(static_cast<double>(sq_distances[0]));
    const double d2 = std::sqrt(static_cast<double>(sq_distances[1]));
    // The tree's distances are float (relative error ~1e-7), and so are its points (their ulp at the query's
    // magnitude); the margin is many times both.
    const double ulp = std::numeric_limits<float>::epsilon() * std::max(1.0, q.cwiseAbs().maxCoeff());
    const double reach = 0.5 * (d2 - d1) - 1e-4 * d2 - 16.0 * ulp;
    if (reach > 0.0) reach_[i] = reach;
  }
  return &sample_[i];
}

SurfacePoint PairCache::closest(const TriangleIndex& surface, std::size_t i, const Eigen::Vector3d& query,
                                double max_distance) {
  std::int32_t* slots = slots_.data() + i * kMaxSlots;
  const double moved = reach_[i] > kNoAnchor ? (query - anchor_[i]).norm() : std::numeric_limits<double>::infinity();
  if (reach_[i] >= 0.0 && moved <= reach_[i]) {
    return surface.closest_among(query, slots, slot_count_[i], max_distance);
  }
  anchor_[i] = query;
  reach_[i] = kNoSlots;
  // Slots only once the point has settled (it moved little against its distance since its last search): while ICP
  // still takes big steps they would be left at once, and collecting them costs a second search.
  // Nor again at a distance where they were too many, until the point is much closer.
  if (!(moved < 0.25 * std::max(distance_[i], 1e-3)) || !(distance_[i] < 0.5 * crowded_[i])) {
    const SurfacePoint best = surface.closest(query, max_distance);
    distance_[i] = best.found() ? std::sqrt(best.sq_distance) : std::numeric_limits<double>::infinity();
    return best;
  }
  thread_local std::vector<std::int32_t> found;
  double reach = 0.0;
  // The reach: at least the point's own distance (about its noise, late in ICP) and 1 um, and twice its last move
  // (ICP's steps shrink, so that covers the next few).
  const SurfacePoint best =
      surface.closest_with_slots(query, max_distance, std::max(1e-3, 2.0 * moved), kMaxSlots, found, &reach);
  distance_[i] = best.found() ? std::sqrt(best.sq_distance) : std::numeric_limits<double>::infinity();
  if (!best.found()) return best;
  if (found.empty()) {
    crowded_[i] = distance_[i];
    return best;
  }
  reach_[i] = reach;
  std::copy(found.begin(), found.end(), slots);
  slot_count_[i] = static_cast<std::uint8_t>(found.size());
  return best;
}

}  // namespace conform::detail
