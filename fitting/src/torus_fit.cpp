#include <cmath>
#include <cstddef>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/sphere_manifold.h>
#include <Eigen/Geometry>

#include "conform/fitting/revolved.h"
#include "revolved_solve.h"

namespace conform {
namespace {

// The orthogonal distances of all the points from the torus in one cost function. Parameters: the unit axis a (3, on
// the sphere), the centre c (3), the major radius R (1) and the minor radius r (1). With q = p - c, h = q.a,
// w = q - h a, rho = |w| and s = |(rho - R, h)| (the distance from the tube's centre circle), the residual d = s - r has
//   dd/dq = ((rho - R) w / rho + h a) / s = -dd/dc,   dd/da = (-(rho - R) h w / rho + h q) / s,
//   dd/dR = -(rho - R) / s,   dd/dr = -1.
// Radii <= 0 fail the evaluation: Ceres then rejects the step.
class TorusDistances final : public ceres::CostFunction {
 public:
  explicit TorusDistances(const std::vector<Eigen::Vector3d>& points) : points_(points) {
    set_num_residuals(static_cast<int>(points.size()));
    *mutable_parameter_block_sizes() = {3, 3, 1, 1};
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> a(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> c(parameters[1]);
    const double major = parameters[2][0], minor = parameters[3][0];
    if (!(major > 0.0 && minor > 0.0)) return false;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector3d q = points_[i] - c;
      const double h = q.dot(a);
      const Eigen::Vector3d w = q - h * a;
      const double rho = w.norm();
      const double s = std::hypot(rho - major, h);
      residuals[i] = s - minor;
      if (jacobians == nullptr) continue;
      // On the axis rho, on the tube's centre circle s, has no derivative: those terms are left out there.
      const Eigen::Vector3d radial = rho > 0.0 ? Eigen::Vector3d(w / rho) : Eigen::Vector3d::Zero();
      const double along = s > 0.0 ? (rho - major) / s : 0.0, up = s > 0.0 ? h / s : 0.0;
      if (jacobians[0] != nullptr) {
        const Eigen::Vector3d d_a = -along * h * radial + up * q;
        for (int j = 0; j < 3; ++j) jacobians[0][3 * i + static_cast<std::size_t>(j)] = d_a[j];
      }
      if (jacobians[1] != nullptr) {
        const Eigen::Vector3d d_c = -(along * radial + up * a);
        for (int j = 0; j < 3; ++j) jacobians[1][3 * i + static_cast<std::size_t>(j)] = d_c[j];
      }
      if (jacobians[2] != nullptr) jacobians[2][i] = -along;
      if (jacobians[3] != nullptr) jacobians[3][i] = -1.0;
    }
    return true;
  }

 private:
  const std::vector<Eigen::Vector3d>& points_;
};

}  // namespace

double torus_distance(const TorusFit& torus, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - torus.centre;
  const double h = d.dot(torus.axis);
  const double rho = (d - h * torus.axis).norm();
  return std::hypot(rho - torus.major_radius_mm, h) - torus.minor_radius_mm;
}

TorusFit fit_torus(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& axis, double major_radius_mm, double minor_radius_mm) {
  TorusFit fit;
  if (points.size() < 8 || !(axis.norm() > 0.0) || !axis.allFinite() || !centre.allFinite() ||
      !(major_radius_mm > 0.0 && minor_radius_mm > 0.0)) {
    return fit;
  }
  std::vector<Eigen::Vector3d> q;
  Eigen::Vector3d centroid;
  if (!detail::centre_points(points, q, centroid)) return fit;
  const Eigen::Vector3d a0 = axis.normalized(), c0 = centre - centroid;
  double axis_block[3] = {a0.x(), a0.y(), a0.z()};
  double centre_block[3] = {c0.x(), c0.y(), c0.z()};
  double major_block[1] = {major_radius_mm};
  double minor_block[1] = {minor_radius_mm};

  ceres::SphereManifold<3> sphere;
  const detail::RevolvedOutcome out =
      detail::solve_revolved(new TorusDistances(q), {axis_block, centre_block, major_block, minor_block}, sphere);

  fit.axis = Eigen::Vector3d(axis_block[0], axis_block[1], axis_block[2]).normalized();
  fit.centre = Eigen::Vector3d(centre_block[0], centre_block[1], centre_block[2]) + centroid;
  fit.major_radius_mm = major_block[0];
  fit.minor_radius_mm = minor_block[0];
  fit.rms_mm = std::sqrt(out.sum_squares / static_cast<double>(q.size()));
  fit.iterations = out.iterations;
  const bool in_range = fit.major_radius_mm > 0.0 && fit.minor_radius_mm > 0.0 && fit.axis.allFinite() &&
                        fit.centre.allFinite();
  fit.ok = out.converged && out.conditioned && in_range && std::isfinite(fit.rms_mm);
  return fit;
}

}  // namespace conform
