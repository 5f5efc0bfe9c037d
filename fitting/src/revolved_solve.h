#pragma once
// The Ceres solve shared by the cone and torus fits (private to the fitting module): the solver's settings and the
// outcome's judgement (converged, well conditioned).

#include <vector>

#include <ceres/cost_function.h>
#include <ceres/manifold.h>
#include <Eigen/Core>

namespace conform::detail {

struct RevolvedOutcome {
  bool converged = false;
  bool conditioned = false;
  double sum_squares = 0.0;  // of the residuals at the solution
  int iterations = 0;
};

// Minimises `cost` (all the points' residuals in one block; the problem takes ownership) over `blocks`, the first the
// unit axis on `axis_manifold`, by Levenberg-Marquardt on one thread, leaving the solution in the blocks; then judges
// the Jacobian there: well conditioned when, its columns (in the tangent space) scaled to unit length, the smallest
// eigenvalue of J^T J is above 1e-12 of the largest.
RevolvedOutcome solve_revolved(ceres::CostFunction* cost, const std::vector<double*>& blocks,
                               ceres::Manifold& axis_manifold);

// relative = points - their centroid; false (nothing to fit) when there is no point or a point is not finite.
bool centre_points(const std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Vector3d>& relative,
                   Eigen::Vector3d& centroid);

}  // namespace conform::detail
