#pragma once
// Geometric least-squares refinement of a cylinder with Ceres (private to the fitting module).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/fitting/cylinder.h"

namespace conform::detail {

struct RefineSettings {
  double loss_scale_mm = 1.0;  // Huber loss scale
  double min_radius_mm = 0.0;
  double max_radius_mm = 0.0;  // infinity: no upper bound
  int max_iterations = 100;
  double tolerance = 1e-12;  // function, gradient and parameter tolerances
};

struct RefineOutcome {
  Cylinder model;  // axis_point: the axis point in the plane through the origin across the starting axis
  bool converged = false;
  int iterations = 0;
  std::string message;  // Ceres's termination message
};

// Minimises sum rho(|(p - c) x a| - r) over points[indices] (centred coordinates), starting from `start`.
RefineOutcome refine_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices,
                              const Cylinder& start, const RefineSettings& settings);

}  // namespace conform::detail
