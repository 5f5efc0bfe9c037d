#pragma once
// The reference's thin walls: plates whose two faces are parallel and close. A scan of such a part from one side sees
// one face of each plate; shifted through the plate by its thickness, the scan lies on the far faces and fits almost
// as well (a one-side scan of a welded bracket, 5 mm plates: 98 % of the scan on the reference, exit 0 with a pose
// 3.3 deg and 5.7 mm off; docs/measurements/cad.md). The coarse stage probes those shifts (multi_start.h).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/registration/icp_reference.h"

namespace conform {

struct ThinWall {
  double thickness_mm = 0.0;  // between the faces, along their normal (the median of the samples found at it)
  double share = 0.0;         // of the sampled reference points, those on a wall of this thickness
  // The walls' normal directions: the principal directions of the sampled walls' normals (unit, sign-free), those
  // that hold at least ThinWallOptions::min_direction_share of their scatter, largest first (1-3).
  std::vector<Eigen::Vector3d> directions;
};

struct ThinWallOptions {
  double max_thickness_mm = 0.0;  // walls up to this thick are looked for (> 0)
  std::size_t samples = 2000;     // reference points tested, an even stride
  // The faces of a wall: the far face's normal within this angle of the near one's.
  double parallel_deg = 20.0;
  // A thickness held by at least this share of the samples is a thin-walled part: most of its surface is plate (the
  // brackets of 3-10 mm plates: 0.70-0.85). Not a fold, a thin rim, or the double surfaces that fusing or repeated
  // sweeps leave in a scene (3DMatch fragments 0.11-0.20, a LiDAR frame 0.11; docs/measurements/cad.md).
  double min_share = 0.3;
  double min_direction_share = 0.1;
  std::size_t max_walls = 2;  // the most common thicknesses, at most this many
};

// The thin walls of the reference, most common first; empty when none. From each sampled point the reference is
// searched along its normal, both ways, in steps of its point spacing from two spacings out to max_thickness_mm: the
// first nearest reference point within 0.75 spacings of the line's point, whose normal is parallel (parallel_deg),
// is the far face. The thicknesses found are grouped where they lie within two spacings of each other.
std::vector<ThinWall> thin_walls(const IcpReference& reference, const ThinWallOptions& options);

}  // namespace conform
