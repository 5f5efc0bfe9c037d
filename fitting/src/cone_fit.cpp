#include <cmath>
#include <cstddef>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/sphere_manifold.h>
#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/fitting/revolved.h"
#include "revolved_solve.h"

namespace conform {
namespace {

// The orthogonal distances of all the points from the cone in one cost function (one block per point costs Ceres
// block bookkeeping, as in cylinder_refine.cpp). Parameters: the unit axis a (3, on the sphere), the axis point
// c = u e1 + v e2 in the plane through the centroid across the start's axis (2: a point of a line has a free
// coordinate along it), the radius r in the plane through c across a (1) and the half-angle alpha (1). With
// q = p - c, h = q.a, w = q - h a, rho = |w|, the residual d = rho cos alpha - r cos alpha - h sin alpha has
//   dd/dq = cos alpha w / rho - sin alpha a,   dd/da = -cos alpha h w / rho - sin alpha q,   dq/d(u, v) = -(e1, e2),
//   dd/dr = -cos alpha,   dd/dalpha = -(rho - r) sin alpha - h cos alpha.
// Parameters out of range (r <= 0, alpha outside (0, pi/2)) fail the evaluation: Ceres then rejects the step.
class ConeDistances final : public ceres::CostFunction {
 public:
  ConeDistances(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2)
      : points_(points), e1_(e1), e2_(e2) {
    set_num_residuals(static_cast<int>(points.size()));
    *mutable_parameter_block_sizes() = {3, 2, 1, 1};
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> a(parameters[0]);
    const Eigen::Vector3d c = parameters[1][0] * e1_ + parameters[1][1] * e2_;
    const double r = parameters[2][0], alpha = parameters[3][0];
    if (!(r > 0.0 && alpha > 0.0 && alpha < kHalfPi)) return false;
    const double cos_a = std::cos(alpha), sin_a = std::sin(alpha);
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector3d q = points_[i] - c;
      const double h = q.dot(a);
      const Eigen::Vector3d w = q - h * a;
      const double rho = w.norm();
      residuals[i] = (rho - r) * cos_a - h * sin_a;
      if (jacobians == nullptr) continue;
      // On the axis itself rho has no derivative: its terms are left out there.
      const Eigen::Vector3d radial = rho > 0.0 ? Eigen::Vector3d(w / rho) : Eigen::Vector3d::Zero();
      if (jacobians[0] != nullptr) {
        const Eigen::Vector3d d_a = -cos_a * h * radial - sin_a * q;
        for (int j = 0; j < 3; ++j) jacobians[0][3 * i + static_cast<std::size_t>(j)] = d_a[j];
      }
      if (jacobians[1] != nullptr) {
        const Eigen::Vector3d d_q = cos_a * radial - sin_a * a;
        jacobians[1][2 * i] = -d_q.dot(e1_);
        jacobians[1][2 * i + 1] = -d_q.dot(e2_);
      }
      if (jacobians[2] != nullptr) jacobians[2][i] = -cos_a;
      if (jacobians[3] != nullptr) jacobians[3][i] = -(rho - r) * sin_a - h * cos_a;
    }
    return true;
  }

 private:
  const std::vector<Eigen::Vector3d>& points_;
  Eigen::Vector3d e1_;
  Eigen::Vector3d e2_;
};

}  // namespace

double cone_distance(const ConeFit& cone, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - cone.axis_point;
  const double h = d.dot(cone.axis);
  const double rho = (d - h * cone.axis).norm();
  return (rho - cone.radius_mm - h * std::tan(cone.half_angle_rad)) * std::cos(cone.half_angle_rad);
}

ConeFit fit_cone(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& apex, const Eigen::Vector3d& axis,
                 double half_angle_rad) {
  ConeFit fit;
  if (points.size() < 7 || !(half_angle_rad > 0.0 && half_angle_rad < kHalfPi) || !(axis.norm() > 0.0) ||
      !apex.allFinite() || !axis.allFinite()) {
    return fit;
  }
  std::vector<Eigen::Vector3d> q;
  Eigen::Vector3d centroid;
  if (!detail::centre_points(points, q, centroid)) return fit;
  const Eigen::Vector3d a0 = axis.normalized();
  const Eigen::Vector3d e1 = a0.unitOrthogonal(), e2 = a0.cross(e1);
  // The start: the nominal cone's axis point in the plane through the centroid across its axis, its radius there.
  const Eigen::Vector3d start_point = apex - centroid - (apex - centroid).dot(a0) * a0;
  const double start_height = (centroid - apex).dot(a0);
  double axis_block[3] = {a0.x(), a0.y(), a0.z()};
  double point_block[2] = {start_point.dot(e1), start_point.dot(e2)};
  double radius_block[1] = {start_height * std::tan(half_angle_rad)};
  double angle_block[1] = {half_angle_rad};
  if (!(radius_block[0] > 0.0)) return fit;  // the centroid on the apex's near side: not this cone

  ceres::SphereManifold<3> sphere;
  const detail::RevolvedOutcome out = detail::solve_revolved(
      new ConeDistances(q, e1, e2), {axis_block, point_block, radius_block, angle_block}, sphere);

  fit.axis = Eigen::Vector3d(axis_block[0], axis_block[1], axis_block[2]).normalized();
  fit.axis_point = point_block[0] * e1 + point_block[1] * e2 + centroid;
  fit.radius_mm = radius_block[0];
  fit.half_angle_rad = angle_block[0];
  fit.apex = fit.axis_point - fit.radius_mm / std::tan(fit.half_angle_rad) * fit.axis;
  fit.rms_mm = std::sqrt(out.sum_squares / static_cast<double>(q.size()));
  fit.iterations = out.iterations;
  const bool in_range = fit.radius_mm > 0.0 && fit.half_angle_rad > 0.0 && fit.half_angle_rad < kHalfPi &&
                        fit.axis.allFinite() && fit.axis_point.allFinite() && fit.apex.allFinite();
  fit.ok = out.converged && out.conditioned && in_range && std::isfinite(fit.rms_mm);
  return fit;
}

}  // namespace conform
