#include "conform/registration/downsample.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {

std::vector<Eigen::Vector3d> voxel_downsample(const std::vector<Eigen::Vector3d>& points, double voxel_mm) {
  if (!(voxel_mm > 0.0) || !std::isfinite(voxel_mm)) {
    throw Error("voxel downsampling: voxel size " + std::to_string(voxel_mm) + " mm must be finite and > 0");
  }
  using Key = std::array<std::int64_t, 3>;
  std::vector<std::pair<Key, std::size_t>> keyed(points.size());
  constexpr double kLimit = 9e15;  // voxel indices must stay exact in double and fit int64
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d cell = (points[i] / voxel_mm).array().floor();
    if (!(cell.cwiseAbs().maxCoeff() < kLimit)) {
      throw Error("voxel downsampling: point " + std::to_string(i) + " is not finite or too far out for " +
                  std::to_string(voxel_mm) + " mm voxels");
    }
    keyed[i] = {
        {static_cast<std::int64_t>(cell.x()), static_cast<std::int64_t>(cell.y()), static_cast<std::int64_t>(cell.z())},
        i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<Eigen::Vector3d> out;
  for (std::size_t begin = 0; begin < keyed.size();) {
    std::size_t end = begin;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (; end < keyed.size() && keyed[end].first == keyed[begin].first; ++end) sum += points[keyed[end].second];
    out.push_back(sum / static_cast<double>(end - begin));
    begin = end;
  }
  return out;
}

std::vector<Eigen::Vector3d> stride_downsample(const std::vector<Eigen::Vector3d>& points, std::size_t count) {
  if (points.size() <= count) return points;
  std::vector<Eigen::Vector3d> out;
  out.reserve(count);
  for (std::size_t k = 0; k < count; ++k) out.push_back(points[k * points.size() / count]);
  return out;
}

double median_spacing(const std::vector<Eigen::Vector3d>& points, const KdTree& tree, std::size_t samples) {
  const std::size_t n = points.size(), count = std::min(n, samples);
  std::vector<double> gaps;
  std::vector<int> indices;
  std::vector<float> sq;
  for (std::size_t k = 0; k < count; ++k) {
    tree.knn(points[k * n / count].cast<float>(), 2, indices, sq);
    if (sq.size() == 2) gaps.push_back(std::sqrt(static_cast<double>(sq[1])));
  }
  if (gaps.empty()) return 0.0;
  std::nth_element(gaps.begin(), gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2), gaps.end());
  return gaps[gaps.size() / 2];
}

}  // namespace conform
