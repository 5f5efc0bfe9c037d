#include "conform/fitting/parametric_surface.h"

#include <algorithm>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace conform {

Eigen::Vector3d ParametricSurface::normal(double u, double v) const {
  const Eigen::Vector3d n = derivative(u, v, 1, 0).cross(derivative(u, v, 0, 1));
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

double FundamentalForms::normal_curvature(double du, double dv) const {
  const double i = first(du, dv);
  return i > 0.0 ? second(du, dv) / i : 0.0;
}

FundamentalForms fundamental_forms(const ParametricSurface& surface, double u, double v) {
  const Eigen::Vector3d ru = surface.derivative(u, v, 1, 0);
  const Eigen::Vector3d rv = surface.derivative(u, v, 0, 1);
  FundamentalForms f;
  f.E = ru.dot(ru);
  f.F = ru.dot(rv);
  f.G = rv.dot(rv);
  const Eigen::Vector3d n = ru.cross(rv);
  const double length = n.norm();
  if (length == 0.0) return f;
  f.normal = n / length;
  f.L = surface.derivative(u, v, 2, 0).dot(f.normal);
  f.M = surface.derivative(u, v, 1, 1).dot(f.normal);
  f.N = surface.derivative(u, v, 0, 2).dot(f.normal);
  return f;
}

bool project_to_surface(const ParametricSurface& surface, const Eigen::Vector3d& p, double* u, double* v,
                        int iterations) {
  const ParameterDomain d = surface.domain();
  for (int it = 0; it < iterations; ++it) {
    const Eigen::Vector3d e = surface.position(*u, *v) - p;
    const Eigen::Vector3d ru = surface.derivative(*u, *v, 1, 0), rv = surface.derivative(*u, *v, 0, 1);
    Eigen::Matrix2d J;
    J << ru.dot(ru) + e.dot(surface.derivative(*u, *v, 2, 0)), ru.dot(rv) + e.dot(surface.derivative(*u, *v, 1, 1)),
        ru.dot(rv) + e.dot(surface.derivative(*u, *v, 1, 1)), rv.dot(rv) + e.dot(surface.derivative(*u, *v, 0, 2));
    const Eigen::Vector2d g(e.dot(ru), e.dot(rv));
    Eigen::Vector2d step = J.fullPivLu().solve(-g);
    if (!step.allFinite()) return false;
    const double limit = 0.5 * std::max(d.u_max - d.u_min, d.v_max - d.v_min);
    if (step.norm() > limit) step *= limit / step.norm();
    *u = std::clamp(*u + step.x(), d.u_min, d.u_max);
    *v = std::clamp(*v + step.y(), d.v_min, d.v_max);
    if (step.norm() < 1e-12) return true;
  }
  return false;
}

}  // namespace conform
