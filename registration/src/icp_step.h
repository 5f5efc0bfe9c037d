#pragma once
// One ICP step from a set of weighted pairs: Horn's closed form (point-to-point, all six degrees of freedom free) or
// a Gauss-Newton step on the linearised rotation, restricted to a basis of allowed directions.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/registration/degeneracy.h"
#include "pairs.h"

namespace conform::detail {

// The directions a step may take, as orthonormal columns in the scaled coordinates (rotation x L, translation):
// the free degrees of freedom, without the degenerate ones when `freeze` is set.
Eigen::MatrixXd allowed_basis(const FreeDof& free_dof, const DegeneracyReport& degeneracy, bool freeze);

// The incremental transform (applied on the left of T_ref_scan) minimising the weighted point-to-point distances.
Eigen::Isometry3d horn_step(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers,
                            const std::vector<double>& weights);

// Gauss-Newton on the method's residuals (3D for point-to-point, 3D weighted by both points' plane covariances for
// plane-to-plane with gicp_epsilon, along the normal otherwise), linearised about the pairs' centroid `centre` with
// length scale L, within span(basis).
Eigen::Isometry3d gauss_newton_step(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers,
                                    const std::vector<double>& weights, IcpMethod method, const Eigen::Vector3d& centre,
                                    double length_scale_mm, const Eigen::MatrixXd& basis, double gicp_epsilon = 1e-3);

// The step minimising the linearised objective with normal equations H y = -g (scaled twists about `centre`, length
// scale L), within span(basis).
Eigen::Isometry3d solve_step(const Matrix6d& H, const Vector6d& g, const Eigen::Vector3d& centre,
                             double length_scale_mm, const Eigen::MatrixXd& basis);

}  // namespace conform::detail
