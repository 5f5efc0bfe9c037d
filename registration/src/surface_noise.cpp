#include "conform/registration/surface_noise.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {

bool SurfaceNoiseOptions::IsValid(std::string* error) const {
  std::string why;
  if (neighbours < 5) {
    why = "neighbours must be >= 5";
  } else if (samples == 0) {
    why = "samples must be >= 1";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

double estimate_surface_noise(const std::vector<Eigen::Vector3d>& points, const SurfaceNoiseOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("surface noise options: " + why);
  const auto k = static_cast<std::size_t>(options.neighbours);
  if (points.size() < k) return 0.0;
  const KdTree tree(points);  // throws for a non-finite point
  return estimate_surface_noise(points, tree, options);
}

double estimate_surface_noise(const std::vector<Eigen::Vector3d>& points, const KdTree& tree,
                              const SurfaceNoiseOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("surface noise options: " + why);
  const auto k = static_cast<std::size_t>(options.neighbours);
  if (points.size() < k) return 0.0;
  const std::size_t count = std::min(options.samples, points.size());
  std::vector<double> sigmas(count);
  const double correction = static_cast<double>(k) / static_cast<double>(k - 3);
#pragma omp parallel for schedule(dynamic, 64) if (count > 256)
  for (std::ptrdiff_t s = 0; s < static_cast<std::ptrdiff_t>(count); ++s) {
    std::vector<int> indices;
    std::vector<float> sq;
    const std::size_t i = static_cast<std::size_t>(s) * points.size() / count;
    tree.knn(points[i].cast<float>(), options.neighbours, indices, sq);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int j : indices) mean += points[static_cast<std::size_t>(j)];
    mean /= static_cast<double>(indices.size());
    Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
    for (int j : indices) {
      const Eigen::Vector3d d = points[static_cast<std::size_t>(j)] - mean;
      C.noalias() += d * d.transpose();
    }
    C /= static_cast<double>(indices.size());
    const double lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C, Eigen::EigenvaluesOnly).eigenvalues()(0);
    sigmas[static_cast<std::size_t>(s)] = std::sqrt(std::max(0.0, lambda) * correction);
  }
  const auto middle = sigmas.begin() + static_cast<std::ptrdiff_t>(sigmas.size() / 2);
  std::nth_element(sigmas.begin(), middle, sigmas.end());
  return *middle;
}

}  // namespace conform
