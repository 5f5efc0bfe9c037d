#include "revolved_solve.h"

#include <cstddef>
#include <cstdint>

#include <ceres/cost_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>
#include <Eigen/Eigenvalues>

#include "conform/core/geometry.h"

namespace conform::detail {
namespace {

constexpr int kRevolvedMaxIterations = 100;
constexpr double kRevolvedTolerance = 1e-12;       // function, gradient and parameter tolerances
constexpr double kRevolvedMinConditioning = 1e-12;  // smallest / largest eigenvalue of the scaled J^T J

ceres::Solver::Options revolved_options() {
  ceres::Solver::Options options;
  options.minimizer_type = ceres::TRUST_REGION;
  options.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  // Six or seven unknowns over thousands of rows: a dense QR of the Jacobian does not square its condition number.
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = kRevolvedMaxIterations;
  options.function_tolerance = kRevolvedTolerance;
  options.gradient_tolerance = kRevolvedTolerance;
  options.parameter_tolerance = kRevolvedTolerance;
  options.num_threads = 1;  // the same bits on every run
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  return options;
}

// The Jacobian of `cost` at `blocks` in the tangent space (the axis block, blocks[0], through the manifold's plus
// Jacobian), its columns scaled to unit length: J^T J far from singular when the data determine every parameter.
bool well_conditioned(const ceres::CostFunction& cost, const std::vector<double*>& blocks,
                      const ceres::Manifold& axis_manifold) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const auto rows = static_cast<Eigen::Index>(cost.num_residuals());
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  std::vector<RowMajor> ambient;
  std::vector<double*> jacobians;
  for (const int32_t size : sizes) {
    ambient.emplace_back(rows, size);
    jacobians.push_back(ambient.back().data());
  }
  Eigen::VectorXd residuals(rows);
  if (!cost.Evaluate(blocks.data(), residuals.data(), jacobians.data())) return false;
  RowMajor plus(axis_manifold.AmbientSize(), axis_manifold.TangentSize());
  if (!axis_manifold.PlusJacobian(blocks[0], plus.data())) return false;
  Eigen::Index columns = plus.cols();
  for (std::size_t k = 1; k < sizes.size(); ++k) columns += sizes[k];
  Eigen::MatrixXd jacobian(rows, columns);
  jacobian.leftCols(plus.cols()) = ambient[0] * plus;
  Eigen::Index at = plus.cols();
  for (std::size_t k = 1; k < sizes.size(); ++k) {
    jacobian.middleCols(at, sizes[k]) = ambient[k];
    at += sizes[k];
  }
  const Eigen::MatrixXd jtj = jacobian.transpose() * jacobian;
  const Eigen::VectorXd scale = jtj.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * jtj * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled, Eigen::EigenvaluesOnly);
  const Eigen::VectorXd values = eigen.eigenvalues();
  return values(columns - 1) > 0.0 && values(0) > kRevolvedMinConditioning * values(columns - 1);
}

}  // namespace

RevolvedOutcome solve_revolved(ceres::CostFunction* cost, const std::vector<double*>& blocks,
                               ceres::Manifold& axis_manifold) {
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(cost, nullptr, blocks);
  problem.SetManifold(blocks[0], &axis_manifold);
  ceres::Solver::Summary summary;
  ceres::Solve(revolved_options(), &problem, &summary);
  RevolvedOutcome out;
  out.converged = summary.termination_type == ceres::CONVERGENCE && summary.IsSolutionUsable();
  out.sum_squares = 2.0 * summary.final_cost;  // Ceres's cost is half the sum of squares
  out.iterations = summary.num_successful_steps + summary.num_unsuccessful_steps;
  out.conditioned = out.converged && well_conditioned(*cost, blocks, axis_manifold);
  return out;
}

bool centre_points(const std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Vector3d>& relative,
                   Eigen::Vector3d& centroid) {
  if (points.empty()) return false;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) return false;
  }
  centroid = conform::centroid(points);
  relative.clear();
  relative.reserve(points.size());
  for (const Eigen::Vector3d& p : points) relative.push_back(p - centroid);
  return true;
}

}  // namespace conform::detail
