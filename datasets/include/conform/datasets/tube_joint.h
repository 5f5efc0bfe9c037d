#pragma once
// `generate tube-joint`: a posed pair of scans for `conform tube-joint` — the outer surface of a leg (a patch of a
// large tube around the joint, in the leg frame L) and the inner surface of a stub (a full tube, in the stub frame S)
// — with their deformations and scanner effects (datasets/tube.h), and the ground truth: the intersection curve of
// the noise-free deformed surfaces, sampled densely by stub azimuth.
//
// Frames (toolpath/intersection/joint_frames.h; datasets does not depend on toolpath, so the caller passes T_L_S):
//   leg   its tube frame is L: z along the leg axis, the leg tube spans z_L in [-length/2, length/2].
//   stub  its tube frame is S shifted: the stub spans z_S in [0, stub length] (z_S = 0 the distal end, z towards the
//         leg), azimuth from x_S (the toe). By default the stub ends the margin beyond the curve's deepest point when
//         its end ring then lies wholly inside the leg, else on the leg's axis (z_S = protrusion): either way its open
//         end is inside the leg and the meshes meet in one closed curve. The stub's bump heights z_mm are z_S.
//
// Ground truth (independent of any mesh): for each stub azimuth phi, the stub's deformed inner wall
// z -> S_stub(phi, z) is marched from the distal end towards the leg and the first root of
//   f(z) = |q_xy| - r_leg(atan2(q_y, q_x), q_z),  q = T_L_S * S_stub(phi, z)
// (outside the leg f > 0) is bracketed and bisected to 1e-9 mm.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/mesh.h"
#include "conform/datasets/tube_options.h"

namespace conform {

struct TubeJointOptions {
  Eigen::Isometry3d T_L_S = Eigen::Isometry3d::Identity();  // the joint's pose (toolpath T_L_S(spec))
  double protrusion_mm = 1500.0;  // Delta, the stub's distal end to the leg axis along the stub axis (as in T_L_S)

  // Leg and stub as generate_tube makes them. Used: nominal radius (leg: outer; stub: inner), deformations (ovality,
  // seam, bumps; bow must be 0), triangulation (edge_mm or vertex_count), scanner effects, seed. Replaced: length,
  // arc, surface and T_world_tube (see above).
  TubeOptions leg;
  TubeOptions stub;
  double stub_length_mm = 0.0;   // 0: automatic (above); > 0: this length
  double leg_length_mm = 0.0;    // 0: the curve's extent along the leg axis plus twice the margin, symmetric about 0
  double leg_arc_rad = 0.0;      // 0: a patch covering the curve plus the margin; 2 pi: the closed leg tube
  double leg_margin_mm = 100.0;  // beyond the curve, around the leg patch
  int truth_points = 3600;       // stub azimuths sampled for the ground truth, >= 8

  bool IsValid(std::string* error) const;
};

struct TubeJointTruth {
  std::vector<double> phi_rad;          // stub azimuths, k 2 pi / truth_points
  std::vector<Eigen::Vector3d> points;  // the exact intersection in S, mm
  std::vector<double> stub_z_mm;        // z_S of each point (its height on the stub wall)
  TubeOptions leg;                      // as generated (length, arc, surface filled in)
  TubeOptions stub;
  Eigen::Isometry3d T_S_stub_tube = Eigen::Isometry3d::Identity();
};

struct TubeJointScans {
  Mesh leg_L;   // the leg's outer surface, in L
  Mesh stub_S;  // the stub's inner surface, in S
  TubeJointTruth truth;
};

// The ground truth only (no meshes), for given options. Throws conform::Error when the stub does not reach the leg
// at some azimuth (naming it), or when the options are invalid.
TubeJointTruth tube_joint_truth(const TubeJointOptions& options);

// Truth and meshes. Throws as tube_joint_truth and generate_tube do.
TubeJointScans generate_tube_joint(const TubeJointOptions& options);

// Radial distance of a point given in S from the leg's deformed (noise-free) surface, mm: > 0 outside the leg.
double leg_surface_distance(const TubeJointTruth& truth, const Eigen::Isometry3d& T_L_S, const Eigen::Vector3d& p_S);

// Distance from p to the closed polyline of the truth points, mm.
double distance_to_truth(const TubeJointTruth& truth, const Eigen::Vector3d& p_S);

}  // namespace conform
