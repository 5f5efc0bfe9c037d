#include "conform/evaluation/pose_error.h"

#include <cmath>

namespace conform {

PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Matrix3d r = a.linear().transpose() * b.linear();
  // 2 sin(angle) is the length of the skew part's axis vector, 2 cos(angle) + 1 the trace (Rodrigues' formula).
  const Eigen::Vector3d skew(r(2, 1) - r(1, 2), r(0, 2) - r(2, 0), r(1, 0) - r(0, 1));
  PoseError error;
  error.rotation_rad = std::atan2(0.5 * skew.norm(), 0.5 * (r.trace() - 1.0));
  error.translation_mm = (b.translation() - a.translation()).norm();
  return error;
}

}  // namespace conform
