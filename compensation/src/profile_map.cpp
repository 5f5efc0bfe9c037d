#include "conform/compensation/profile_map.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kMinAcross = 1e-9;  // |Z x C'| / |C'| below this: the tangent is parallel to Z

}  // namespace

ProfileMap::ProfileMap(ProfileEdgeCurve edge, const Eigen::Vector3d& web_normal, double tolerance_mm)
    : edge_(std::move(edge)), tolerance_mm_(tolerance_mm) {
  if (!web_normal.allFinite() || !(web_normal.norm() > 0.0)) {
    throw Error("profile map: the web normal must be a finite, non-zero vector");
  }
  z_ = web_normal.normalized();
}

ProfileMap::ProfileMap(ProfileEdgeCurve edge, ProfileEdgeCurve second_edge, double tolerance_mm)
    : edge_(std::move(edge)), second_(std::move(second_edge)), local_(true), tolerance_mm_(tolerance_mm) {}

Eigen::Vector3d ProfileMap::across_local(const Eigen::Vector3d& p, const Eigen::Vector3d& tangent, double ty_mm,
                                         double* width_mm) const {
  // Foot of the perpendicular from p on the second edge: Newton on g(u) = (C2(u) - p) . C2'(u), started at the same
  // fraction of the length (the edges run side by side).
  const double lo = second_.t_begin(), hi = second_.t_end();
  double u = second_.approximate_parameter_at(ty_mm * second_.length_mm() / edge_.length_mm());
  for (int iteration = 0; iteration < 30; ++iteration) {
    const Eigen::Vector3d d = second_.position(u) - p;
    const Eigen::Vector3d d1 = second_.derivative(u, 1);
    const double g = d.dot(d1);
    const double dg = d1.squaredNorm() + d.dot(second_.derivative(u, 2));
    if (!(dg > 0.0)) break;
    const double next = std::clamp(u - g / dg, lo, hi);
    const bool done = std::abs(next - u) <= 1e-12 * (hi - lo);
    u = next;
    if (done) break;
  }
  const Eigen::Vector3d d = second_.position(u) - p;
  const Eigen::Vector3d across = d - d.dot(tangent) * tangent;
  *width_mm = across.norm();
  if (!(*width_mm > kMinAcross)) throw Error("profile map: the second edge meets the first edge");
  return across / *width_mm;
}

ProfileMappedPoint ProfileMap::map(double tx_mm, double ty_mm) const {
  ProfileMappedPoint out;
  const ArcLengthInverse inverse = edge_.parameter_at(ty_mm, tolerance_mm_);  // Eq. (7)
  out.t = inverse.t;
  out.arc_length_residual_mm = inverse.residual_mm;
  const Eigen::Vector3d c = edge_.position(out.t);
  const Eigen::Vector3d tangent = edge_.derivative(out.t, 1).normalized();
  if (local_) {
    out.across = across_local(c, tangent, ty_mm, &out.local_width_mm);
  } else {
    const Eigen::Vector3d v = z_.cross(tangent);  // Eq. (5)-(6)
    if (!(v.norm() > kMinAcross)) {
      throw Error("profile map: the edge tangent is parallel to the web normal at Ty = " + std::to_string(ty_mm) +
                  " mm");
    }
    out.across = v.normalized();
  }
  out.position = c + tx_mm * out.across;  // Eq. (6)
  out.tangent = tangent;
  out.normal = tangent.cross(out.across).normalized();
  return out;
}

ProfileWebNormal fit_profile_web_normal(const std::vector<Eigen::Vector3d>& points, double min_flatness_ratio) {
  if (points.size() < 3) throw Error("profile web normal: at least 3 points are needed to fit the web plane");
  // Relative to the first point: shop coordinates far from the origin lose no digits.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p - points.front();
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - points.front() - centroid;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Eigen::Vector3d values = solver.eigenvalues().cwiseMax(0.0);
  ProfileWebNormal out;
  out.flatness_ratio = values(0) > 0.0 ? std::sqrt(values(1) / values(0)) : INFINITY;
  if (!(out.flatness_ratio >= min_flatness_ratio)) {
    char text[300];
    std::snprintf(text, sizeof(text),
                  "profile web normal: the measured points lie too nearly on a line to define the web plane "
                  "(flatness ratio %.2f < %.2f); give the web normal (--web-normal x,y,z) or a second edge "
                  "(--second-edge FILE)",
                  out.flatness_ratio, min_flatness_ratio);
    throw Error(text);
  }
  out.normal = solver.eigenvectors().col(0).normalized();
  if (out.normal.z() < 0.0) out.normal = -out.normal;
  return out;
}

}  // namespace conform
