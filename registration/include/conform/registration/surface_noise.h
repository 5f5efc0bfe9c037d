#pragma once
// A cloud's own noise, from the cloud alone: how far points lie from the plane through their neighbours. Against it
// a registration's residuals say whether the pose is consistent (residuals near the noise) or not (residuals many
// times the noise: a wrong pose, or a part far from its reference).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

class KdTree;

struct SurfaceNoiseOptions {
  int neighbours = 16;         // k, the plane fit's support (>= 5)
  std::size_t samples = 2000;  // an even stride of this many points is examined (all when fewer)

  bool IsValid(std::string* error) const;
};

// The median over the sampled points of sqrt(lambda_min k / (k - 3)), lambda_min the smallest eigenvalue of the
// covariance of a point's k nearest neighbours (the plane fit leaves k - 3 degrees of freedom to the noise): the
// noise's standard deviation along the normal, mm, for Gaussian noise on a surface that is flat over k points. The
// median ignores edges and corners. 0 for fewer than k points. Throws conform::Error for invalid options or a
// non-finite point.
double estimate_surface_noise(const std::vector<Eigen::Vector3d>& points, const SurfaceNoiseOptions& options = {});
// The same over a kd-tree the caller already holds; `tree` indexes `points`.
double estimate_surface_noise(const std::vector<Eigen::Vector3d>& points, const KdTree& tree,
                              const SurfaceNoiseOptions& options = {});

}  // namespace conform
