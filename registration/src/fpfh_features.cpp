#include "fpfh_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <nanoflann.hpp>

#include "conform/core/nearest_neighbors.h"

namespace conform::detail {

namespace {

constexpr float kPi = 3.14159265358979323846f;

// A histogram bin of `value` in [lo, lo + span], clamped to the ends (rounding can step just outside).
int bin(float value, float lo, float span) {
  const int b = static_cast<int>(std::floor(static_cast<float>(kFpfhBins) * ((value - lo) / span)));
  return std::clamp(b, 0, kFpfhBins - 1);
}

struct Neighbourhood {
  std::vector<int> indices;
  std::vector<float> sq_distances;
};

// The SPFH of point i (three histograms of kFpfhBins, in the layout of FpfhHistogram) over its neighbourhood.
void spfh(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector3f>& normals, std::size_t i,
          const Neighbourhood& near, float* histogram) {
  std::fill(histogram, histogram + 3 * kFpfhBins, 0.0f);
  if (near.indices.size() < 2 || !normals[i].allFinite()) return;
  const float increment = 100.0f / static_cast<float>(near.indices.size() - 1);
  Eigen::Vector3f angles;
  for (const int j : near.indices) {
    const auto k = static_cast<std::size_t>(j);
    if (k == i || !normals[k].allFinite()) continue;
    if (!pair_angles(points[i], normals[i], points[k], normals[k], angles)) continue;
    histogram[bin(angles[0], -kPi, 2.0f * kPi)] += increment;
    histogram[kFpfhBins + bin(angles[1], -1.0f, 2.0f)] += increment;
    histogram[2 * kFpfhBins + bin(angles[2], -1.0f, 2.0f)] += increment;
  }
}

}  // namespace

std::vector<std::size_t> statistical_inliers(const std::vector<Eigen::Vector3f>& points, int k, double sigmas) {
  std::vector<std::size_t> kept;
  const std::size_t n = points.size();
  if (k <= 0 || n <= static_cast<std::size_t>(k)) {
    kept.resize(n);
    for (std::size_t i = 0; i < n; ++i) kept[i] = i;
    return kept;
  }
  std::vector<Eigen::Vector3d> as_double(n);
  for (std::size_t i = 0; i < n; ++i) as_double[i] = points[i].cast<double>();
  const KdTree tree(as_double);
  std::vector<double> mean_distance(n);
#pragma omp parallel
  {
    std::vector<int> indices;
    std::vector<float> sq_distances;
#pragma omp for schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
      tree.knn(points[static_cast<std::size_t>(i)], k + 1, indices, sq_distances);
      double sum = 0.0;  // the first is the point itself (or a copy of it at distance 0)
      for (std::size_t j = 1; j < sq_distances.size(); ++j) sum += std::sqrt(static_cast<double>(sq_distances[j]));
      mean_distance[static_cast<std::size_t>(i)] = sum / static_cast<double>(k);
    }
  }
  double sum = 0.0, sq_sum = 0.0;
  for (const double d : mean_distance) {
    sum += d;
    sq_sum += d * d;
  }
  const double mean = sum / static_cast<double>(n);
  const double variance = std::max(0.0, (sq_sum - sum * sum / static_cast<double>(n)) / static_cast<double>(n - 1));
  const double limit = mean + sigmas * std::sqrt(variance);
  for (std::size_t i = 0; i < n; ++i) {
    if (mean_distance[i] <= limit) kept.push_back(i);
  }
  return kept;
}

bool pair_angles(const Eigen::Vector3f& p1, const Eigen::Vector3f& n1, const Eigen::Vector3f& p2,
                 const Eigen::Vector3f& n2, Eigen::Vector3f& angles) {
  angles.setZero();
  Eigen::Vector3f line = p2 - p1;
  const float d = line.norm();
  if (d == 0.0f) return false;
  // The source is the end whose normal makes the smaller angle with the line, so that a pair gives the same
  // angles whichever of its points asks.
  const float cos1 = n1.dot(line) / d, cos2 = n2.dot(line) / d;
  Eigen::Vector3f u = n1, target = n2;
  float phi = cos1;
  if (std::acos(std::min(1.0f, std::abs(cos1))) > std::acos(std::min(1.0f, std::abs(cos2)))) {
    u = n2;
    target = n1;
    line = -line;
    phi = -cos2;
  }
  Eigen::Vector3f v = line.cross(u);
  const float v_norm = v.norm();
  if (v_norm == 0.0f) return false;
  v /= v_norm;
  const Eigen::Vector3f w = u.cross(v);
  angles = Eigen::Vector3f(std::atan2(w.dot(target), u.dot(target)), v.dot(target), phi);
  return true;
}

std::vector<FpfhHistogram> fpfh_histograms(const std::vector<Eigen::Vector3f>& points,
                                           const std::vector<Eigen::Vector3f>& normals, float radius) {
  const std::size_t n = points.size();
  std::vector<Eigen::Vector3d> as_double(n);
  for (std::size_t i = 0; i < n; ++i) as_double[i] = points[i].cast<double>();
  const KdTree tree(as_double);
  std::vector<Neighbourhood> near(n);
  std::vector<float> spfhs(n * 3 * kFpfhBins);
  const auto count = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    tree.radius(points[k], radius, near[k].indices, near[k].sq_distances);
    spfh(points, normals, k, near[k], spfhs.data() + k * 3 * kFpfhBins);
  }
  std::vector<FpfhHistogram> out(n);
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const auto k = static_cast<std::size_t>(i);
    FpfhHistogram& h = out[k];
    if (!normals[k].allFinite()) {
      h.fill(std::numeric_limits<float>::quiet_NaN());
      continue;
    }
    h.fill(0.0f);
    double sums[3] = {0.0, 0.0, 0.0};
    for (std::size_t m = 0; m < near[k].indices.size(); ++m) {
      if (near[k].sq_distances[m] == 0.0f) continue;  // the point itself
      const float weight = 1.0f / near[k].sq_distances[m];
      const float* s = spfhs.data() + static_cast<std::size_t>(near[k].indices[m]) * 3 * kFpfhBins;
      for (int b = 0; b < 3 * kFpfhBins; ++b) {
        const float value = s[b] * weight;
        sums[b / kFpfhBins] += value;
        h[static_cast<std::size_t>(b)] += value;
      }
    }
    for (int b = 0; b < 3 * kFpfhBins; ++b) {
      const double sum = sums[b / kFpfhBins];
      if (sum != 0.0)
        h[static_cast<std::size_t>(b)] = static_cast<float>(h[static_cast<std::size_t>(b)] * (100.0 / sum));
    }
  }
  return out;
}

struct HistogramIndex::Impl {
  // nanoflann's view of the rows kept (finite histograms).
  std::vector<const FpfhHistogram*> rows;
  std::vector<std::size_t> original;
  std::size_t kdtree_get_point_count() const { return rows.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*rows[i])[dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Impl, float, std::uint32_t>,
                                                   Impl, 3 * kFpfhBins, std::uint32_t>;
  std::unique_ptr<Tree> tree;
};

HistogramIndex::HistogramIndex(const std::vector<FpfhHistogram>& histograms) : impl_(std::make_unique<Impl>()) {
  for (std::size_t i = 0; i < histograms.size(); ++i) {
    if (!std::all_of(histograms[i].begin(), histograms[i].end(), [](float v) { return std::isfinite(v); })) continue;
    impl_->rows.push_back(&histograms[i]);
    impl_->original.push_back(i);
  }
  impl_->tree = std::make_unique<Impl::Tree>(3 * kFpfhBins, *impl_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

HistogramIndex::~HistogramIndex() = default;

void HistogramIndex::knn(const FpfhHistogram& query, int k, std::vector<std::size_t>& indices,
                         std::vector<float>& sq_distances) const {
  const auto capacity = static_cast<std::size_t>(std::max(0, std::min<int>(k, static_cast<int>(impl_->rows.size()))));
  std::vector<std::uint32_t> found(capacity);
  sq_distances.resize(capacity);
  indices.clear();
  if (capacity == 0) return;
  nanoflann::KNNResultSet<float, std::uint32_t> result(capacity);
  result.init(found.data(), sq_distances.data());
  impl_->tree->findNeighbors(result, query.data(), nanoflann::SearchParams());
  const std::size_t got = result.size();
  sq_distances.resize(got);
  for (std::size_t m = 0; m < got; ++m) indices.push_back(impl_->original[found[m]]);
}

}  // namespace conform::detail
