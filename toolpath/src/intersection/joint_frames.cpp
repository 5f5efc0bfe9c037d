#include "conform/toolpath/intersection/joint_frames.h"

#include "conform/core/constants.h"

#include <cmath>
#include <sstream>

namespace conform {
bool TubeJointSpec::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!std::isfinite(pitch_rad) || !std::isfinite(offset_mm) || !std::isfinite(protrusion_mm)) {
    why << "the joint's pitch, offset and protrusion must be finite numbers";
  } else if (!(pitch_rad > 0.0 && pitch_rad <= kHalfPi)) {
    why << "pitch " << pitch_rad * 90.0 / kHalfPi << " deg is outside (0, 90] deg";
  }
  if (why.tellp() == 0) return true;
  if (error != nullptr) *error = why.str();
  return false;
}

Eigen::Vector2d pitch_cos_sin(double pitch_rad) {
  // pi/2 - pitch is exact for pitch near pi/2, so the T joint gets cos = 0 and sin = 1 exactly.
  const double complement = kHalfPi - pitch_rad;
  return {std::sin(complement), std::cos(complement)};
}

Eigen::Isometry3d T_L_S(const TubeJointSpec& spec) {
  const Eigen::Vector2d cs = pitch_cos_sin(spec.pitch_rad);
  // Rotation by the pitch about -y: x' = (cos, 0, sin), y' = y, z' = (-sin, 0, cos).
  Eigen::Matrix3d rotation;
  rotation.col(0) << cs.x(), 0.0, cs.y();
  rotation.col(1) << 0.0, 1.0, 0.0;
  rotation.col(2) << -cs.y(), 0.0, cs.x();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation;
  // Then the offset along y' and the protrusion along -z', both in the rotated frame.
  T.translation() = rotation * Eigen::Vector3d(0.0, spec.offset_mm, -spec.protrusion_mm);
  return T;
}

Eigen::Isometry3d T_S_P(const TubeJointSpec& spec) {
  Eigen::Matrix3d rotation;
  rotation.col(0) << 0.0, 1.0, 0.0;   // x_P = y_S
  rotation.col(1) << 1.0, 0.0, 0.0;   // y_P = x_S (towards the toe)
  rotation.col(2) << 0.0, 0.0, -1.0;  // z_P = -z_S (away from the leg)
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation;
  T.translation() = Eigen::Vector3d(0.0, 0.0, spec.protrusion_mm);
  return T;
}

Eigen::Isometry3d T_L_P(const TubeJointSpec& spec) { return T_L_S(spec) * T_S_P(spec); }

}  // namespace conform
