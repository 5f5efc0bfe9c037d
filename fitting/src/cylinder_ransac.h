#pragma once
// RANSAC for a cylinder on points with normals (private to the fitting module): two points and their normals per
// sample, MSAC scoring on a seeded subset, the consensus set of the best hypothesis over all points.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/cylinder.h"

namespace conform::detail {

struct RansacSettings {
  double threshold_mm = 1.0;               // inlier distance to the surface
  double cos_normal = 0.8660254037844387;  // inlier: |n . radial| >= this
  double min_radius_mm = 0.0;
  double max_radius_mm = 0.0;
  Eigen::Vector3d axis_prior = Eigen::Vector3d::Zero();  // unit, or zero for none
  double cos_prior = 0.0;                                // |a . prior| >= this
  double sin_min_normal_angle = 0.0871557427476582;      // |n1 x n2| below this: the sample gives no axis
  int max_iterations = 2000;
  int min_iterations = 100;
  double confidence = 0.999;
  int sample_points = 4000;
  std::uint64_t seed = 1;
};

struct RansacOutcome {
  bool found = false;               // at least one hypothesis passed the checks
  Cylinder model;                   // the best hypothesis; axis_point is the axis point nearest the origin
  std::vector<int> inliers;         // of the best hypothesis, over all points, ascending
  int iterations = 0;               // samples drawn
  int parallel_normal_samples = 0;  // samples rejected because their normals were (nearly) parallel
};

// Points centred on their centroid; normals unit (sign ignored).
RansacOutcome ransac_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                              const RansacSettings& settings);

// True when p agrees with the cylinder: within threshold of the surface and its normal within the angle of the
// surface normal. *distance receives the signed distance to the surface.
bool agrees(const Cylinder& model, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double threshold_mm,
            double cos_normal, double* distance);

}  // namespace conform::detail
