#include "conform/fitting/bspline_curve.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "conform/core/error.h"

namespace conform {

BSplineCurve::BSplineCurve(std::vector<Eigen::Vector3d> control_points, bool closed, double u_begin, double u_end)
    : control_(std::move(control_points)), closed_(closed), u_begin_(u_begin), u_end_(u_end) {
  if (control_.size() < 4) {
    throw Error("B-spline curve: " + std::to_string(control_.size()) + " control points; a cubic needs at least 4");
  }
  for (std::size_t i = 0; i < control_.size(); ++i) {
    if (!control_[i].allFinite()) throw Error("B-spline curve: control point " + std::to_string(i) + " is not finite");
  }
  if (!(std::isfinite(u_begin) && std::isfinite(u_end) && u_end > u_begin)) {
    throw Error("B-spline curve: the parameter domain must be finite with u_end > u_begin");
  }
  h_ = (u_end_ - u_begin_) / spans();
}

int BSplineCurve::spans() const {
  const int m = static_cast<int>(control_.size());
  return closed_ ? m : m - 3;
}

void BSplineCurve::locate(double u, int* span, double* x, int indices[4]) const {
  const int n = spans();
  const int m = static_cast<int>(control_.size());
  double v = (u - u_begin_) / h_;  // in spans from u_begin
  if (closed_) {
    v -= n * std::floor(v / n);
    if (!(v < n)) v = 0.0;  // rounding put a parameter just below the seam onto it
  }
  const int j = std::clamp(static_cast<int>(std::floor(v)), 0, n - 1);  // open: the end spans extrapolate
  *span = j;
  *x = v - j;
  for (int k = 0; k < 4; ++k) indices[k] = closed_ ? (j + k) % m : j + k;
}

void BSplineCurve::basis(double x, int order, double b[4]) {
  const double y = 1.0 - x;
  switch (order) {
    case 0:
      b[0] = y * y * y / 6.0;
      b[1] = (3.0 * x * x * x - 6.0 * x * x + 4.0) / 6.0;
      b[2] = (-3.0 * x * x * x + 3.0 * x * x + 3.0 * x + 1.0) / 6.0;
      b[3] = x * x * x / 6.0;
      return;
    case 1:
      b[0] = -0.5 * y * y;
      b[1] = 0.5 * (3.0 * x * x - 4.0 * x);
      b[2] = 0.5 * (-3.0 * x * x + 2.0 * x + 1.0);
      b[3] = 0.5 * x * x;
      return;
    case 2:
      b[0] = y;
      b[1] = 3.0 * x - 2.0;
      b[2] = 1.0 - 3.0 * x;
      b[3] = x;
      return;
    case 3:
      b[0] = -1.0;
      b[1] = 3.0;
      b[2] = -3.0;
      b[3] = 1.0;
      return;
    default:
      b[0] = b[1] = b[2] = b[3] = 0.0;
  }
}

Eigen::Vector3d BSplineCurve::derivative(double u, int order) const {
  if (order < 0) throw Error("B-spline curve: derivative order must be >= 0");
  if (order > 3 || control_.empty()) return Eigen::Vector3d::Zero();
  int span = 0;
  double x = 0.0;
  int idx[4];
  locate(u, &span, &x, idx);
  double b[4];
  basis(x, order, b);
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) value += b[k] * control_[static_cast<std::size_t>(idx[k])];
  // h^order; the first two orders multiplied out (pow's cost on every speed evaluation).
  const double factor = order == 0 ? 1.0 : order == 1 ? h_ : order == 2 ? h_ * h_ : std::pow(h_, order);
  return value / factor;
}

// Span by span: the third derivative jumps at the knots, so the speed is smooth only between them, and a quadrature
// rule across a knot would need many more bisections for the same tolerance.
double BSplineCurve::arc_length(double u0, double u1, const ArcLengthOptions& options) const {
  const SpeedFunction speed_at = [this](double u) { return speed(u); };
  const double lo = std::min(u0, u1), hi = std::max(u0, u1);
  double total = 0.0;
  for (double a = lo; a < hi;) {
    double knot = u_begin_ + (std::floor((a - u_begin_) / h_) + 1.0) * h_;
    if (!(knot > a)) knot += h_;
    if (!closed_ && a < u_begin_) knot = u_begin_;
    if (!closed_ && a >= u_end_) knot = hi;
    const double b = std::min(knot, hi);
    total += conform::arc_length(speed_at, a, b, options);
    a = b;
  }
  return u1 >= u0 ? total : -total;
}

}  // namespace conform
