#pragma once
// `conform generate tube-joint`: a posed leg + stub scan pair for `conform tube-joint` (datasets/tube_joint.h) from
// the joint (pitch, offset, protrusion), the radii and wall, deformations, mesh edge length and noise, with the
// ground truth (the intersection of the noise-free deformed surfaces) as CSV. The three files appear together or
// not at all; the same options give the same bytes.

#include <cstddef>
#include <string>

#include "conform/core/io.h"
#include "conform/datasets/tube_joint.h"
#include "conform/toolpath/intersection/joint_frames.h"

namespace conform {

// The automatic protrusion (GenerateTubeJointOptions::spec.protrusion_mm <= 0) leaves the stub's distal end this far
// clear of the leg, mm.
inline constexpr double kAutoStubClearanceMm = 100.0;

struct GenerateTubeJointOptions {
  TubeJointSpec spec;                   // protrusion_mm <= 0: automatic, the distal end kAutoStubClearanceMm clear
  double stub_outer_radius_mm = 500.0;  // the stub's outer radius, mm
  double wall_mm = 25.0;                // the stub's wall: its scanned inner radius is outer - wall, mm
  // Leg (radius_mm = its outer radius) and stub (radius_mm ignored: outer - wall) deformations, edge length, noise,
  // seed (see datasets/tube_joint.h). The leg's bump z is z_L, the stub's z_S.
  TubeJointOptions joint;
  std::string leg_path;    // .ply or .stl, the leg's outer surface in L
  std::string stub_path;   // .ply or .stl, the stub's inner surface in S
  std::string truth_path;  // .csv: phi_rad,x_mm,y_mm,z_mm in S
  Encoding encoding = Encoding::kBinary;

  bool IsValid(std::string* error) const;
};

struct GenerateTubeJointResult {
  TubeJointSpec spec;  // with the protrusion used
  double stub_inner_radius_mm = 0.0;
  std::size_t leg_faces = 0;
  std::size_t stub_faces = 0;
  double leg_length_mm = 0.0;
  double leg_arc_rad = 0.0;
  double stub_length_mm = 0.0;
  std::size_t truth_points = 0;
};

// The protrusion that puts the distal end `clearance_mm` beyond the leg (for nominal cylinders).
double automatic_protrusion(double pitch_rad, double leg_radius_mm, double stub_radius_mm, double clearance_mm);

// Throws conform::Error naming the option or the file. A failure leaves none of the files behind.
GenerateTubeJointResult run_generate_tube_joint(const GenerateTubeJointOptions& options);

// The truth CSV text: `phi_rad,x_mm,y_mm,z_mm`, 9 decimals.
std::string tube_joint_truth_csv(const TubeJointTruth& truth);

}  // namespace conform
