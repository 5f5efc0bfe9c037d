#pragma once
// Analytic parametric surfaces for the path tests: a plane, a cylinder and a sphere with exact derivatives.

#include <cmath>

#include "conform/fitting/parametric_surface.h"

namespace conform::test {

// r(u, v) = (u, v, 0) over [0, 100]^2.
class Plane : public ParametricSurface {
 public:
  ParameterDomain domain() const override { return {0.0, 100.0, 0.0, 100.0}; }
  Eigen::Vector3d derivative(double u, double v, int du, int dv) const override {
    if (du == 0 && dv == 0) return {u, v, 0.0};
    if (du == 1 && dv == 0) return Eigen::Vector3d::UnitX();
    if (du == 0 && dv == 1) return Eigen::Vector3d::UnitY();
    return Eigen::Vector3d::Zero();
  }
};

// r(u, v) = (R cos u, R sin u, v): u the angle, v along the axis; r_u x r_v points outward (convex).
class Cylinder : public ParametricSurface {
 public:
  explicit Cylinder(double radius) : R(radius) {}
  ParameterDomain domain() const override { return {-3.0, 3.0, -100.0, 100.0}; }
  Eigen::Vector3d derivative(double u, double v, int du, int dv) const override {
    if (dv == 0) {
      const double c = std::cos(u), s = std::sin(u);
      switch (du) {
        case 0: return {R * c, R * s, v};
        case 1: return {-R * s, R * c, 0.0};
        case 2: return {-R * c, -R * s, 0.0};
        default: return {R * s, -R * c, 0.0};
      }
    }
    return (dv == 1 && du == 0) ? Eigen::Vector3d(Eigen::Vector3d::UnitZ()) : Eigen::Vector3d(Eigen::Vector3d::Zero());
  }
  double R;
};

// r(u, v) = R (cos v cos u, cos v sin u, sin v): u longitude, v latitude; r_u x r_v points outward (convex).
class Sphere : public ParametricSurface {
 public:
  explicit Sphere(double radius) : R(radius) {}
  ParameterDomain domain() const override { return {-3.0, 3.0, -1.4, 1.4}; }
  Eigen::Vector3d derivative(double u, double v, int du, int dv) const override {
    // d^du/du^du of (cos u, sin u) and d^dv/dv^dv of (cos v, sin v) by phase shifts.
    const double cu = std::cos(u + du * M_PI / 2), su = std::sin(u + du * M_PI / 2);
    const double cv = std::cos(v + dv * M_PI / 2), sv = std::sin(v + dv * M_PI / 2);
    return {R * cv * cu, R * cv * su, du == 0 ? R * sv : 0.0};
  }
  double R;
};

}  // namespace conform::test
