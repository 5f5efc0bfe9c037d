#pragma once
// A smooth parametric surface r(u, v) over a rectangle of parameters, and what differential geometry needs of it:
// the first and second fundamental forms and the normal curvature in a direction (do Carmo, Differential Geometry of
// Curves and Surfaces, 2-2 and 3-2). The Bézier network (bezier_network.h) and the tests' analytic cylinders and
// spheres implement it; the parallel weld paths (toolpath/weld/parallel_paths.h) work on any of them.

#include <Eigen/Core>

namespace conform {

struct ParameterDomain {
  double u_min = 0.0;
  double u_max = 1.0;
  double v_min = 0.0;
  double v_max = 1.0;
  bool contains(double u, double v, double slack = 0.0) const {
    return u >= u_min - slack && u <= u_max + slack && v >= v_min - slack && v <= v_max + slack;
  }
};

class ParametricSurface {
 public:
  virtual ~ParametricSurface() = default;
  virtual ParameterDomain domain() const = 0;
  // d^(du + dv) r / du^du dv^dv at (u, v), du + dv <= 2, mm per parameter unit to that power.
  virtual Eigen::Vector3d derivative(double u, double v, int du, int dv) const = 0;

  Eigen::Vector3d position(double u, double v) const { return derivative(u, v, 0, 0); }
  // r_u x r_v, normalised; zero where the surface is singular.
  Eigen::Vector3d normal(double u, double v) const;
};

// First (E, F, G) and second (L, M, N) fundamental forms at a point, with the unit normal r_u x r_v / |r_u x r_v|.
struct FundamentalForms {
  double E = 0.0, F = 0.0, G = 0.0;
  double L = 0.0, M = 0.0, N = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();

  double first(double du, double dv) const { return E * du * du + 2.0 * F * du * dv + G * dv * dv; }
  double second(double du, double dv) const { return L * du * du + 2.0 * M * du * dv + N * dv * dv; }
  // k_n = II / I in the parameter direction (du, dv), 1/mm: negative where the surface bends away from its normal
  // (convex seen from the normal's side), 0 for a zero direction.
  double normal_curvature(double du, double dv) const;
};

FundamentalForms fundamental_forms(const ParametricSurface& surface, double u, double v);

// The point of `surface` closest to p by Newton's method on (r - p) . r_u = (r - p) . r_v = 0 from (u, v), clamped to
// the domain. Returns false (and the last iterate) when it did not converge in `iterations`.
bool project_to_surface(const ParametricSurface& surface, const Eigen::Vector3d& p, double* u, double* v,
                        int iterations = 30);

}  // namespace conform
