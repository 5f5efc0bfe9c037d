#include "cylinder_refine.h"

#include <cmath>
#include <cstddef>
#include <vector>

#include <ceres/ceres.h>
#include <ceres/sphere_manifold.h>
#include <Eigen/Geometry>

namespace conform::detail {
namespace {

// The axis point lives in a plane across the starting axis (two coordinates along e1, e2): the point of a line has a
// free coordinate along the line, which would leave the normal equations singular.
struct PlaneBasis {
  Eigen::Vector3d e1;
  Eigen::Vector3d e2;
};

// All the inliers' residuals in one cost function: one residual block per point costs Ceres ~5x the time in block
// bookkeeping, for 50k points. The geometric residual |q x a| - r with q = p - (u e1 + v e2) (orthogonal, so unbiased
// under noise, where the algebraic |q x a|^2 - r^2 is not) has the analytic derivatives, with w = q x a, rho = |w|:
//   d rho / d a = (w x q) / rho,   d rho / d q = (a x w) / rho,   d q / d(u, v) = -(e1, e2),   d / d r = -1.
// Ceres's LossFunction would act on the block's whole norm, so the Huber loss (scale k) is applied per residual here:
// f = r for |r| <= k, sign(r) sqrt(2 k |r| - k^2) beyond, so that f^2 / 2 is Huber's rho(r^2) / 2 term by term and the
// least-squares problem on f is the robust problem on r (df/dr = k / |f| beyond k; continuous at |r| = k).
class SurfaceDistances final : public ceres::CostFunction {
 public:
  SurfaceDistances(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices, const PlaneBasis& basis,
                   double huber_scale)
      : points_(points), indices_(indices), basis_(basis), k_(huber_scale) {
    set_num_residuals(static_cast<int>(indices.size()));
    *mutable_parameter_block_sizes() = {3, 2, 1};
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> a(parameters[0]);
    const Eigen::Vector3d c = parameters[1][0] * basis_.e1 + parameters[1][1] * basis_.e2;
    const double r = parameters[2][0];
    for (std::size_t i = 0; i < indices_.size(); ++i) {
      const Eigen::Vector3d q = points_[static_cast<std::size_t>(indices_[i])] - c;
      const Eigen::Vector3d w = q.cross(a);
      const double rho = w.norm();
      const double d = rho - r;
      const double f = std::abs(d) <= k_ ? d : std::copysign(std::sqrt(2.0 * k_ * std::abs(d) - k_ * k_), d);
      residuals[i] = f;
      if (jacobians == nullptr) continue;
      const double df = std::abs(d) <= k_ ? 1.0 : k_ / std::abs(f);
      // On the axis itself the distance has no derivative; a zero row leaves that point out of the step.
      const bool on_axis = !(rho > 0.0);
      const Eigen::Vector3d d_a = on_axis ? Eigen::Vector3d::Zero() : Eigen::Vector3d(df * w.cross(q) / rho);
      const Eigen::Vector3d d_q = on_axis ? Eigen::Vector3d::Zero() : Eigen::Vector3d(df * a.cross(w) / rho);
      if (jacobians[0] != nullptr) {
        for (int j = 0; j < 3; ++j) jacobians[0][3 * i + static_cast<std::size_t>(j)] = d_a[j];
      }
      if (jacobians[1] != nullptr) {
        jacobians[1][2 * i] = -d_q.dot(basis_.e1);
        jacobians[1][2 * i + 1] = -d_q.dot(basis_.e2);
      }
      if (jacobians[2] != nullptr) jacobians[2][i] = -df;
    }
    return true;
  }

 private:
  const std::vector<Eigen::Vector3d>& points_;
  const std::vector<int>& indices_;
  const PlaneBasis& basis_;
  double k_;
};

ceres::Solver::Options solver_options(const RefineSettings& s) {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  // Six unknowns over thousands of rows: a dense QR of the Jacobian is cheap and does not square its condition number,
  // which the normal equations would (their Cholesky factorisation fails outright on a plane's runaway radius).
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = s.max_iterations;
  options.function_tolerance = s.tolerance;
  options.gradient_tolerance = s.tolerance;
  options.parameter_tolerance = s.tolerance;
  options.num_threads = 1;  // one thread: the sums (and so every step) are the same bits on every run
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

}  // namespace

RefineOutcome refine_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& indices,
                              const Cylinder& start, const RefineSettings& s) {
  const Eigen::Vector3d a0 = start.axis_direction.normalized();
  PlaneBasis basis;
  basis.e1 = a0.unitOrthogonal();
  basis.e2 = a0.cross(basis.e1);
  double axis[3] = {a0.x(), a0.y(), a0.z()};
  double centre[2] = {start.axis_point.dot(basis.e1), start.axis_point.dot(basis.e2)};
  double radius[1] = {start.radius_mm};

  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  ceres::SphereManifold<3> sphere;
  problem.AddResidualBlock(new SurfaceDistances(points, indices, basis, s.loss_scale_mm), nullptr, axis, centre,
                           radius);
  problem.SetManifold(axis, &sphere);
  if (s.min_radius_mm > 0.0) problem.SetParameterLowerBound(radius, 0, s.min_radius_mm);
  if (std::isfinite(s.max_radius_mm)) problem.SetParameterUpperBound(radius, 0, s.max_radius_mm);

  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(s), &problem, &summary);

  RefineOutcome out;
  out.model.axis_direction = Eigen::Vector3d(axis[0], axis[1], axis[2]).normalized();
  out.model.axis_point = centre[0] * basis.e1 + centre[1] * basis.e2;
  out.model.radius_mm = radius[0];
  out.converged = summary.termination_type == ceres::CONVERGENCE && summary.IsSolutionUsable();
  out.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  out.message = summary.message;
  return out;
}

}  // namespace conform::detail
