#include "conform/registration/multi_start.h"

// same_up_to_free (multi_start.h): whether two poses differ only along the free motions the coarse stage found.

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "conform/registration/icp.h"

namespace conform {

namespace {

// The components of d along the (reference-frame) free translations, seen through `R_scan_ref`, taken out.
Eigen::Vector3d without_free(Eigen::Vector3d d, const std::vector<Eigen::Vector3d>& translations,
                             const Eigen::Matrix3d& R_scan_ref) {
  for (const Eigen::Vector3d& t : translations) {
    const Eigen::Vector3d u = R_scan_ref * t;
    d -= d.dot(u) * u;
  }
  return d;
}

}  // namespace

bool same_up_to_free(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b,
                     const std::vector<DegenerateDirection>& free_motions, const Eigen::Vector3d& scan_centre,
                     double max_rad, double max_mm) {
  std::vector<Eigen::Vector3d> translations;
  std::vector<const DegenerateDirection*> rotations;
  for (const DegenerateDirection& d : free_motions) {
    if (d.kind == MotionKind::kRotation) {
      rotations.push_back(&d);
      continue;
    }
    Eigen::Vector3d t = d.direction;  // Gram-Schmidt, so that taking them out one by one is a projection
    for (const Eigen::Vector3d& u : translations) t -= t.dot(u) * u;
    if (t.norm() > 1e-6) translations.push_back(t.normalized());
  }
  const Eigen::Matrix3d R_a = T_a.linear().transpose();  // scan <- reference
  const Eigen::Isometry3d A = T_a.inverse(), B = T_b.inverse();
  if (rotations.empty()) {
    const Eigen::Isometry3d between = T_b * T_a.inverse();
    const Eigen::Vector3d moved = T_b * scan_centre - T_a * scan_centre;
    return rotation_angle(between) <= max_rad &&
           without_free(moved, translations, Eigen::Matrix3d::Identity()).norm() <= max_mm;
  }
  const Eigen::Vector3d& k = rotations.front()->direction;
  const Eigen::Vector3d& point = rotations.front()->point;
  if (rotations.size() > 1) {
    return without_free(A * point - B * point, translations, R_a).norm() <= max_mm;
  }
  const Eigen::Vector3d d_a = A.linear() * k, d_b = B.linear() * k;
  if (std::acos(std::min(1.0, std::abs(d_a.dot(d_b)))) > max_rad) return false;
  const Eigen::Vector3d p_a = A * point, p_b = B * point;
  const Eigen::Vector3d q_a = p_a + (scan_centre - p_a).dot(d_a) * d_a;
  const Eigen::Vector3d q_b = p_b + (scan_centre - p_b).dot(d_b) * d_b;
  Eigen::Vector3d gap = without_free(q_a - q_b, translations, R_a);
  gap -= gap.dot(d_a) * d_a;
  return gap.norm() <= max_mm;
}

}  // namespace conform
