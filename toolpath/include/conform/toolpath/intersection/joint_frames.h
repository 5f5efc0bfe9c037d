#pragma once
// Frames of a tubular joint: a stub (brace, pipe of radius r) saddle-cut onto a leg (chord, cylinder of radius R).
// Conventions of Lind & Ystgaard (2020), shared by `conform tube-joint` and `conform saddle`:
//
//   leg frame L   z along the leg axis; origin on the leg axis at its point closest to the stub axis; x in the plane
//                 through the leg axis parallel to the stub axis, pointing to the side the stub comes from.
//   stub frame S  z along the stub axis, pointing towards the leg; origin at the stub's distal end; x towards the toe.
//   paper frame P the frame of Xue et al. (2018), Fig. 2, generalised: origin on the stub axis at its point closest to
//                 the leg axis; z along the stub axis pointing away from the leg; y = x_S (towards the toe);
//                 x = y_S. The stub azimuth phi (from x_S towards y_S) is the paper's rotation angle theta, and a
//                 point of the stub wall is (r sin phi, r cos phi, h) in P (Xue et al. Eq. 1-3).
//
// T_L_S is composed exactly as Lind & Ystgaard compose it: rotate by the pitch about -y, translate the offset along
// the rotated y', then the protrusion along -z'.

#include <string>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct TubeJointSpec {
  // Pitch theta: angle between the leg axis and the stub axis, rad, in (0, pi/2]. Default pi/2 (a T joint).
  double pitch_rad = 1.5707963267948966;
  // Offset delta: distance between the two axes along y_L (signed), mm. Default 0 (the axes intersect).
  double offset_mm = 0.0;
  // Protrusion Delta: distance from the leg axis's closest point to the stub's distal end along the stub axis, mm.
  // Default 0. Only places the origin of S; the intersection curve in P does not depend on it.
  double protrusion_mm = 0.0;

  // True when all values are finite and the pitch is in (0, pi/2]; otherwise says why in *error (if given).
  bool IsValid(std::string* error) const;
};

// Maps stub coordinates into the leg frame: p_L = T_L_S * p_S.
Eigen::Isometry3d T_L_S(const TubeJointSpec& spec);

// Maps paper-frame coordinates into the stub frame: p_S = T_S_P * p_P.
Eigen::Isometry3d T_S_P(const TubeJointSpec& spec);

// Maps paper-frame coordinates into the leg frame: T_L_S * T_S_P.
Eigen::Isometry3d T_L_P(const TubeJointSpec& spec);

// cos and sin of the pitch, exact (0 and 1) at pitch_rad == pi/2 so that the T joint is the paper's case bit for bit.
Eigen::Vector2d pitch_cos_sin(double pitch_rad);

}  // namespace conform
