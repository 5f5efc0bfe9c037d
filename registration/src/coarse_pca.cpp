#include "conform/registration/coarse_pca.h"

#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"

namespace conform {

namespace {

bool nearly_equal(double a, double b, double ambiguity) { return std::abs(a - b) <= ambiguity * std::max(a, b); }

// The axis (0, 1, 2) whose plane with another is ambiguous on either side, or -1: turns go about the third one.
int free_plane_normal(const PrincipalAxes& a, const PrincipalAxes& b, double ambiguity) {
  for (const PrincipalAxes* p : {&a, &b}) {
    if (nearly_equal(p->variances(0), p->variances(1), ambiguity)) return 2;
    if (nearly_equal(p->variances(1), p->variances(2), ambiguity)) return 0;
  }
  return -1;
}

}  // namespace

PrincipalAxes principal_axes(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 3) {
    throw Error("principal axes: " + std::to_string(points.size()) + " points; at least 3 are needed");
  }
  PrincipalAxes out;
  for (const Eigen::Vector3d& p : points) out.centroid += p;
  out.centroid /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance.noalias() += (p - out.centroid) * (p - out.centroid).transpose();
  covariance /= static_cast<double>(points.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  // Ascending from the solver; descending here.
  for (int k = 0; k < 3; ++k) {
    out.axes.col(k) = solver.eigenvectors().col(2 - k);
    out.variances(k) = std::max(0.0, solver.eigenvalues()(2 - k));
  }
  out.axes.col(2) = out.axes.col(0).cross(out.axes.col(1));
  return out;
}

std::vector<CoarseStart> pca_starts(const std::vector<Eigen::Vector3d>& scan,
                                    const std::vector<Eigen::Vector3d>& reference, double ambiguity) {
  const PrincipalAxes s = principal_axes(scan), r = principal_axes(reference);
  const int turn_axis = free_plane_normal(s, r, ambiguity);
  // With turns about an axis, flipping that axis (and one other) is the only sign choice left: the other flips
  // are turns of 180 degrees.
  const int turns = turn_axis < 0 ? 1 : 8, flips = turn_axis < 0 ? 4 : 2;
  std::vector<CoarseStart> starts;
  for (int turn = 0; turn < turns; ++turn) {
    for (int flip = 0; flip < flips; ++flip) {
      // Signs of the first two axes; the third follows (a rotation keeps the right hand).
      const double sx = (flip & 1) ? -1.0 : 1.0, sy = (flip & 2) ? -1.0 : 1.0;
      Eigen::Matrix3d scan_axes = s.axes;
      scan_axes.col(0) *= sx;
      scan_axes.col(1) *= sy;
      scan_axes.col(2) *= sx * sy;
      if (turn_axis >= 0) {
        const Eigen::AngleAxisd rotation(turn * M_PI / 4.0, scan_axes.col(turn_axis));
        scan_axes = rotation.toRotationMatrix() * scan_axes;
      }
      CoarseStart start;
      start.label = std::string("pca ") + (sx > 0 ? "+" : "-") + "x" + (sy > 0 ? "+" : "-") + "y" +
                    (turn > 0 ? " turn " + std::to_string(45 * turn) : "");
      start.T_ref_scan.linear() = r.axes * scan_axes.transpose();
      start.T_ref_scan.translation() = r.centroid - start.T_ref_scan.linear() * s.centroid;
      starts.push_back(start);
    }
  }
  return starts;
}

}  // namespace conform
