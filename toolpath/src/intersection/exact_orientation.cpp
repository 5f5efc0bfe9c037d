#include "conform/toolpath/intersection/exact_orientation.h"

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>  // cross(): defined there (it used to link only through PCL's sample_consensus)

namespace conform {
namespace {

// An expansion: a sum of non-overlapping doubles in increasing magnitude (Shewchuk 1997, Sec. 2).
using Expansion = std::vector<double>;

void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double b_virtual = x - a;
  const double a_virtual = x - b_virtual;
  y = (a - a_virtual) + (b - b_virtual);
}

// Grow-Expansion (Shewchuk Theorem 10) with zero elimination.
Expansion grow(const Expansion& e, double b) {
  Expansion out;
  out.reserve(e.size() + 1);
  double q = b;
  for (const double component : e) {
    double sum = 0.0;
    double error = 0.0;
    two_sum(q, component, sum, error);
    if (error != 0.0) out.push_back(error);
    q = sum;
  }
  if (q != 0.0 || out.empty()) out.push_back(q);
  return out;
}

Expansion add(const Expansion& e, const Expansion& f) {
  Expansion out = e;
  for (const double component : f) out = grow(out, component);
  return out;
}

// e * b, exactly: each product split by a fused multiply-add into its rounded value and its rounding error.
Expansion scale(const Expansion& e, double b) {
  Expansion out{0.0};
  for (const double component : e) {
    const double product = component * b;
    const double error = std::fma(component, b, -product);
    out = grow(grow(out, error), product);
  }
  return out;
}

Expansion multiply(const Expansion& e, const Expansion& f) {
  Expansion out{0.0};
  for (const double component : f) out = add(out, scale(e, component));
  return out;
}

Expansion negate(Expansion e) {
  for (double& component : e) component = -component;
  return e;
}

Expansion difference(double a, double b) {
  double x = 0.0;
  double y = 0.0;
  two_sum(a, -b, x, y);
  return y == 0.0 ? Expansion{x} : Expansion{y, x};
}

int sign(const Expansion& e) {
  // Non-overlapping and increasing: the largest non-zero component decides.
  for (auto it = e.rbegin(); it != e.rend(); ++it) {
    if (*it > 0.0) return 1;
    if (*it < 0.0) return -1;
  }
  return 0;
}

int exact_det3_sign(const Eigen::Vector3d& a1, const Eigen::Vector3d& a0, const Eigen::Vector3d& b1,
                    const Eigen::Vector3d& b0, const Eigen::Vector3d& c1, const Eigen::Vector3d& c0) {
  Expansion a[3];
  Expansion b[3];
  Expansion c[3];
  for (int i = 0; i < 3; ++i) {
    a[i] = difference(a1[i], a0[i]);
    b[i] = difference(b1[i], b0[i]);
    c[i] = difference(c1[i], c0[i]);
  }
  const Expansion m0 = add(multiply(b[1], c[2]), negate(multiply(b[2], c[1])));
  const Expansion m1 = add(multiply(b[2], c[0]), negate(multiply(b[0], c[2])));
  const Expansion m2 = add(multiply(b[0], c[1]), negate(multiply(b[1], c[0])));
  return sign(add(add(multiply(a[0], m0), multiply(a[1], m1)), multiply(a[2], m2)));
}

}  // namespace

int det3_sign(const Eigen::Vector3d& a1, const Eigen::Vector3d& a0, const Eigen::Vector3d& b1,
              const Eigen::Vector3d& b0, const Eigen::Vector3d& c1, const Eigen::Vector3d& c0) {
  const Eigen::Vector3d a = a1 - a0;
  const Eigen::Vector3d b = b1 - b0;
  const Eigen::Vector3d c = c1 - c0;
  const double m0 = b.y() * c.z() - b.z() * c.y();
  const double m1 = b.z() * c.x() - b.x() * c.z();
  const double m2 = b.x() * c.y() - b.y() * c.x();
  const double det = a.x() * m0 + a.y() * m1 + a.z() * m2;
  const double permanent = std::abs(a.x()) * (std::abs(b.y() * c.z()) + std::abs(b.z() * c.y())) +
                           std::abs(a.y()) * (std::abs(b.z() * c.x()) + std::abs(b.x() * c.z())) +
                           std::abs(a.z()) * (std::abs(b.x() * c.y()) + std::abs(b.y() * c.x()));
  // Each rounded difference, product and sum adds at most one unit roundoff relative to the permanent; 16 units
  // is a generous bound (Shewchuk's orient3d filter uses 7 for exact differences).
  const double bound = 16.0 * std::numeric_limits<double>::epsilon() * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  return exact_det3_sign(a1, a0, b1, b0, c1, c0);
}

int orient3d_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  return det3_sign(b, a, c, a, d, a);
}

double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

}  // namespace conform
