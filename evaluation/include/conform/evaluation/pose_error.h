#pragma once
// How far apart two rigid transforms are, for accuracy-evaluation scripts (an estimate against the truth, or two
// runs against each other): the angle of the relative rotation and the distance between the translations.

#include <Eigen/Geometry>

namespace conform {

struct PoseError {
  double rotation_rad = 0.0;    // angle of R_a^T R_b, in [0, pi]
  double translation_mm = 0.0;  // |t_b - t_a|, the length of the relative transform's translation
};

// The error of b against a, through E = a^-1 b: rotation_rad is E's rotation angle, translation_mm the length of
// E's translation (= |t_b - t_a|, since a rotation keeps lengths). Symmetric: pose_error(a, b) == pose_error(b, a).
// The angle is atan2(|sin|, cos) from E's skew part and trace, accurate near 0 and near pi (acos of the trace
// alone loses half the digits of small angles).
PoseError pose_error(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

}  // namespace conform
