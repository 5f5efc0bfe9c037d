#include "conform/core/nearest_neighbors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nanoflann.hpp>

#include "conform/core/error.h"

// nanoflann rather than PCL's KdTreeFLANN, by bench/nearest_neighbors_bench.cpp (uniform and scanner-like tube
// clouds of 100k and 1M points, 100k queries, thread CPU time, two runs): this tree builds 1.3-1.8x faster than
// KdTreeFLANN; at 100k points it answers k = 1 2.8-3.3x, k = 10 1.7-1.8x and ~20-neighbour radius queries 1.7x
// faster; at 1M points, where cache misses dominate, k = 1 1.8-2.3x, k = 10 1.4-2.0x and radius 1.2-1.7x faster
// thanks to store_in_leaf_order() (plain nanoflann is 0.9-1.6x there).

namespace conform {

namespace {

// Most points per leaf. 10 and 20 were measured: equal at 100k points, 20 faster at 1M (k = 10 on the uniform cloud
// 0.38 s instead of 0.49 s per 100k queries) once the leaves are contiguous, and a little faster to build.
constexpr std::size_t kLeafSize = 20;

// The bound nanoflann searches within is widened by this relative amount (plus the smallest normal float, so that a
// zero bound still lets exact duplicates through its strict `<`). nanoflann accumulates the squared distance to a
// cell incrementally in float, so it can exceed the distance of a point inside that cell by a few ulps (under 1e-5
// relative even down a 1M-point tree); without the margin a point tied with the current k-th neighbour, or lying
// exactly on the radius, could be skipped and the result would differ from brute force. The exact test is addPoint's.
constexpr float kBoundSlack = 1e-4f;

float widened(float sq_distance) { return sq_distance * (1.0f + kBoundSlack) + std::numeric_limits<float>::min(); }

// Orders neighbours by (squared distance, index): ties resolve to the lower index, so results are deterministic and
// equal to a brute-force sort. Non-negative floats order like their bit patterns, hence the one 64-bit key.
std::uint64_t sort_key(float sq_distance, std::uint32_t index) {
  std::uint32_t bits = 0;
  static_assert(sizeof(bits) == sizeof(sq_distance));
  std::memcpy(&bits, &sq_distance, sizeof(bits));
  return (static_cast<std::uint64_t>(bits) << 32) | index;
}

// The k best (distance, index) pairs, kept sorted in the caller's output vectors (no allocation per query).
// nanoflann reports storage positions; `original` maps them to the caller's indices. kPositions: the output names
// each neighbour by its position rather than its index; the order (ties to the lower index) is the same.
template <bool kPositions>
class KnnResult {
 public:
  KnnResult(std::size_t capacity, const std::uint32_t* original, int* indices, float* sq_distances)
      : capacity_(capacity), original_(original), indices_(indices), sq_distances_(sq_distances) {}

  std::size_t size() const { return count_; }
  bool full() const { return count_ == capacity_; }
  float worstDist() const { return bound_; }                  // NOLINT: name required by nanoflann
  bool addPoint(float sq_distance, std::uint32_t position) {  // NOLINT: name required by nanoflann
    const auto idx = static_cast<int>(original_[position]);
    if (full() && !precedes(sq_distance, idx, capacity_ - 1)) return true;
    std::size_t i = full() ? capacity_ - 1 : count_++;
    for (; i > 0 && precedes(sq_distance, idx, i - 1); --i) {
      sq_distances_[i] = sq_distances_[i - 1];
      indices_[i] = indices_[i - 1];
    }
    sq_distances_[i] = sq_distance;
    indices_[i] = kPositions ? static_cast<int>(position) : idx;
    if (full()) bound_ = widened(sq_distances_[capacity_ - 1]);
    return true;
  }

 private:
  int index_in(std::size_t slot) const {
    return kPositions ? static_cast<int>(original_[static_cast<std::size_t>(indices_[slot])]) : indices_[slot];
  }
  bool precedes(float sq_distance, int index, std::size_t slot) const {
    return sq_distance < sq_distances_[slot] || (sq_distance == sq_distances_[slot] && index < index_in(slot));
  }

  std::size_t capacity_;
  std::size_t count_ = 0;
  const std::uint32_t* original_;
  int* indices_;
  float* sq_distances_;
  float bound_ = std::numeric_limits<float>::infinity();  // search bound: widened k-th distance once k are found
};

// Every point with squared distance <= sq_radius, as sort keys (sorted afterwards).
class RadiusResult {
 public:
  RadiusResult(float sq_radius, const std::uint32_t* original, std::vector<std::uint64_t>& keys)
      : sq_radius_(sq_radius), bound_(widened(sq_radius)), original_(original), keys_(keys) {
    keys_.clear();
  }

  std::size_t size() const { return keys_.size(); }
  bool full() const { return true; }
  float worstDist() const { return bound_; }                  // NOLINT: name required by nanoflann
  bool addPoint(float sq_distance, std::uint32_t position) {  // NOLINT: name required by nanoflann
    if (sq_distance <= sq_radius_) keys_.push_back(sort_key(sq_distance, original_[position]));
    return true;
  }

 private:
  float sq_radius_;
  float bound_;
  const std::uint32_t* original_;
  std::vector<std::uint64_t>& keys_;
};

void check_query(const Eigen::Vector3f& query) {
  if (!query.allFinite()) throw Error("nearest-neighbour search: the query point is not finite (NaN or Inf)");
}

}  // namespace

// The dataset adaptor nanoflann reads from (its method names are nanoflann's), the points and the index over them.
// Impl never moves once built (KdTree moves its unique_ptr), so the index's reference to it stays valid.
struct KdTree::Impl {
  using Metric = nanoflann::L2_Simple_Adaptor<float, Impl, float, std::uint32_t>;
  using Index = nanoflann::KDTreeSingleIndexAdaptor<Metric, Impl, 3, std::uint32_t>;

  std::vector<float> xyz;               // x0 y0 z0 x1 ..., in the tree's leaf order once built
  std::vector<std::uint32_t> original;  // the caller's index of the point stored at each position
  std::unique_ptr<Index> index;

  std::size_t kdtree_get_point_count() const { return xyz.size() / 3; }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return xyz[3 * i + dim]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox& /*bbox*/) const {
    return false;
  }

  void build() {
    const std::size_t n = kdtree_get_point_count();
    if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
      throw Error("nearest-neighbour search: " + std::to_string(n) + " points exceed the int index range");
    }
    std::size_t bad = 0;
    for (std::size_t i = 0; i < n; ++i) {
      bad += std::isfinite(xyz[3 * i]) && std::isfinite(xyz[3 * i + 1]) && std::isfinite(xyz[3 * i + 2]) ? 0 : 1;
    }
    if (bad > 0) {
      throw Error("nearest-neighbour search: " + std::to_string(bad) + " of " + std::to_string(n) +
                  " points are not finite (NaN or Inf); drop them before building the tree");
    }
    if (n == 0) return;
    index = std::make_unique<Index>(3, *this, nanoflann::KDTreeSingleIndexAdaptorParams(kLeafSize));
    store_in_leaf_order();
  }

  // nanoflann leaves the points where they are and reaches a leaf's points through its permutation vAcc, so on a
  // large cloud every point visited is a cache miss. Storing the points in vAcc's order (as FLANN does) makes each
  // leaf contiguous; vAcc becomes the identity and `original` translates positions back. The tree's splits and
  // bounds do not depend on where the points are stored. Measured in bench/nearest_neighbors_bench.cpp.
  void store_in_leaf_order() {
    std::vector<std::uint32_t>& permutation = index->vAcc;
    std::vector<float> ordered(xyz.size());
    original.resize(permutation.size());
    for (std::size_t i = 0; i < permutation.size(); ++i) {
      const std::size_t from = permutation[i];
      std::copy_n(xyz.begin() + static_cast<std::ptrdiff_t>(3 * from), 3,
                  ordered.begin() + static_cast<std::ptrdiff_t>(3 * i));
      original[i] = permutation[i];
      permutation[i] = static_cast<std::uint32_t>(i);
    }
    xyz.swap(ordered);
  }
};

KdTree::KdTree(const pcl::PointCloud<pcl::PointXYZ>& points) : impl_(std::make_unique<Impl>()) {
  impl_->xyz.reserve(3 * points.size());
  for (const pcl::PointXYZ& p : points) impl_->xyz.insert(impl_->xyz.end(), {p.x, p.y, p.z});
  impl_->build();
}

KdTree::KdTree(const std::vector<Eigen::Vector3d>& points) : impl_(std::make_unique<Impl>()) {
  // A double beyond the float range becomes Inf here and is rejected by build() like any non-finite point.
  impl_->xyz.reserve(3 * points.size());
  for (const Eigen::Vector3d& p : points) {
    impl_->xyz.insert(impl_->xyz.end(),
                      {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  }
  impl_->build();
}

KdTree::~KdTree() = default;
KdTree::KdTree(KdTree&&) noexcept = default;
KdTree& KdTree::operator=(KdTree&&) noexcept = default;

std::size_t KdTree::size() const { return impl_ ? impl_->kdtree_get_point_count() : 0; }

template <bool kPositions>
void KdTree::knn_as(const Eigen::Vector3f& query, int k, std::vector<int>& indices,
                    std::vector<float>& sq_distances) const {
  if (k <= 0) throw Error("nearest-neighbour search: k = " + std::to_string(k) + ", must be at least 1");
  check_query(query);
  const std::size_t count = std::min(static_cast<std::size_t>(k), size());
  indices.resize(count);
  sq_distances.resize(count);
  if (count == 0) return;
  KnnResult<kPositions> result(count, impl_->original.data(), indices.data(), sq_distances.data());
  impl_->index->findNeighbors(result, query.data(), nanoflann::SearchParams());
}

void KdTree::knn(const Eigen::Vector3f& query, int k, std::vector<int>& indices,
                 std::vector<float>& sq_distances) const {
  knn_as<false>(query, k, indices, sq_distances);
}

void KdTree::knn_positions(const Eigen::Vector3f& query, int k, std::vector<int>& positions,
                           std::vector<float>& sq_distances) const {
  knn_as<true>(query, k, positions, sq_distances);
}

void KdTree::radius(const Eigen::Vector3f& query, float radius, std::vector<int>& indices,
                    std::vector<float>& sq_distances) const {
  if (!(radius >= 0.0f)) {
    throw Error("nearest-neighbour search: radius = " + std::to_string(radius) + " mm, must be >= 0");
  }
  check_query(query);
  indices.clear();
  sq_distances.clear();
  if (size() == 0) return;
  // One scratch buffer per thread, so that repeated queries do not allocate.
  thread_local std::vector<std::uint64_t> keys;
  RadiusResult result(radius * radius, impl_->original.data(), keys);
  impl_->index->findNeighbors(result, query.data(), nanoflann::SearchParams());
  std::sort(keys.begin(), keys.end());
  indices.resize(keys.size());
  sq_distances.resize(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    indices[i] = static_cast<int>(keys[i] & 0xffffffffu);
    const auto bits = static_cast<std::uint32_t>(keys[i] >> 32);
    std::memcpy(&sq_distances[i], &bits, sizeof(bits));
  }
}

template <bool kPositions>
int KdTree::nearest_as(const Eigen::Vector3f& query, float* sq_distance) const {
  check_query(query);
  int index = -1;
  float best = std::numeric_limits<float>::infinity();
  if (size() > 0) {
    KnnResult<kPositions> result(1, impl_->original.data(), &index, &best);
    impl_->index->findNeighbors(result, query.data(), nanoflann::SearchParams());
  }
  if (sq_distance != nullptr) *sq_distance = best;
  return index;
}

int KdTree::nearest(const Eigen::Vector3f& query, float* sq_distance) const {
  return nearest_as<false>(query, sq_distance);
}

int KdTree::nearest_position(const Eigen::Vector3f& query, float* sq_distance) const {
  return nearest_as<true>(query, sq_distance);
}

const std::vector<std::uint32_t>& KdTree::leaf_order() const {
  static const std::vector<std::uint32_t> kNone;
  return impl_ ? impl_->original : kNone;
}

Eigen::Vector3f KdTree::point_at_position(std::size_t position) const {
  const float* p = impl_->xyz.data() + 3 * position;
  return {p[0], p[1], p[2]};
}

}  // namespace conform
