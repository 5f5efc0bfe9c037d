#pragma once
// Exact signs of 3x3 determinants of double-precision point differences: the orientation predicate the mesh
// intersection builds on. A floating-point filter answers almost every call; when the rounded value is within its
// error bound of zero, the determinant is evaluated exactly with floating-point expansions (Shewchuk 1997, "Adaptive
// precision floating-point arithmetic and fast robust geometric predicates": Two-Sum, Two-Product, Grow-Expansion),
// so a point lying exactly on a triangle's plane gets 0, never a sign made up by rounding.

#include <Eigen/Core>

namespace conform {

// Sign (-1, 0, +1) of det[a1 - a0, b1 - b0, c1 - c0] (rows), exact for any finite doubles (no overflow/underflow).
int det3_sign(const Eigen::Vector3d& a1, const Eigen::Vector3d& a0, const Eigen::Vector3d& b1,
              const Eigen::Vector3d& b0, const Eigen::Vector3d& c1, const Eigen::Vector3d& c0);

// Sign of det[b - a, c - a, d - a] = ((b - a) x (c - a)) . (d - a): +1 when d lies on the side the normal of the
// counter-clockwise triangle (a, b, c) points to, 0 when the four points are coplanar. Exact.
int orient3d_sign(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d);

// The same determinant rounded to double (for interpolation, not for decisions).
double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d);

}  // namespace conform
