#pragma once
// A cubic B-spline space curve on uniform knots, open or closed (periodic).
//
//   open    m >= 4 control points, m - 3 spans of equal length h over [u_begin, u_end]; span j is shaped by control
//           points j .. j + 3. Outside the domain the end spans extrapolate.
//   closed  m >= 4 control points, m spans over one period [u_begin, u_end); span j is shaped by control points
//           j .. j + 3 taken modulo m, so the curve is C2 everywhere, across the seam at u_begin = u_end too.
//           A parameter outside the period is wrapped into it.
// On a span with local parameter x = (u - u_j) / h in [0, 1], the uniform cubic basis (de Boor, A Practical Guide to
// Splines, IX) is b0 = (1 - x)^3 / 6, b1 = (3x^3 - 6x^2 + 4) / 6, b2 = (-3x^3 + 3x^2 + 3x + 1) / 6, b3 = x^3 / 6.

#include <vector>

#include <Eigen/Core>

#include "conform/fitting/arc_length.h"

namespace conform {

class BSplineCurve {
 public:
  BSplineCurve() = default;
  // Throws conform::Error when there are fewer than 4 control points, one is not finite, or u_end <= u_begin.
  BSplineCurve(std::vector<Eigen::Vector3d> control_points, bool closed, double u_begin, double u_end);

  bool closed() const { return closed_; }
  double u_begin() const { return u_begin_; }
  double u_end() const { return u_end_; }
  int spans() const;
  double knot_spacing() const { return h_; }
  const std::vector<Eigen::Vector3d>& control_points() const { return control_; }

  Eigen::Vector3d position(double u) const { return derivative(u, 0); }
  // d^order S / du^order, order in [0, 3] (the third derivative is piecewise constant: it jumps at the knots).
  Eigen::Vector3d derivative(double u, int order = 1) const;
  double speed(double u) const { return derivative(u, 1).norm(); }

  // Signed arc length from u0 to u1 (no wrapping: a closed curve's u1 - u0 may exceed the period), mm.
  double arc_length(double u0, double u1, const ArcLengthOptions& options = {}) const;
  double length(const ArcLengthOptions& options = {}) const { return arc_length(u_begin_, u_end_, options); }

  // For the fit: the span of u, its local parameter x in [0, 1), and the 4 control-point indices it blends.
  void locate(double u, int* span, double* x, int indices[4]) const;
  // The 4 basis values (order 0) or their order-th derivatives in x, at local parameter x.
  static void basis(double x, int order, double b[4]);

 private:
  std::vector<Eigen::Vector3d> control_;
  bool closed_ = false;
  double u_begin_ = 0.0;
  double u_end_ = 1.0;
  double h_ = 1.0;
};

}  // namespace conform
