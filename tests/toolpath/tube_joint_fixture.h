#pragma once
// Shared by the tube-joint tests: a generated leg + stub pair for a joint spec, small enough for a test.

#include <cmath>

#include "conform/datasets/tube_grid.h"
#include "conform/datasets/tube_joint.h"
#include "conform/pipelines/tube_joint/tube_joint.h"
#include "conform/toolpath/intersection/joint_frames.h"

namespace conform::test {

struct JointCase {
  double pitch_deg = 90.0;
  double offset_mm = 0.0;
  double leg_radius_mm = 300.0;
  double stub_radius_mm = 150.0;  // inner
  double edge_mm = 4.0;
};

inline TubeJointSpec joint_spec(const JointCase& c) {
  TubeJointSpec spec;
  spec.pitch_rad = c.pitch_deg / 180.0 * 3.141592653589793;
  spec.offset_mm = c.offset_mm;
  const double s = std::sin(spec.pitch_rad);
  // The distal end clear of the leg: past the leg's radius along the stub axis plus the stub's slant.
  spec.protrusion_mm = c.leg_radius_mm / s + c.stub_radius_mm * std::cos(spec.pitch_rad) / s + 40.0;
  return spec;
}

inline TubeJointOptions joint_options(const JointCase& c) {
  TubeJointOptions o;
  const TubeJointSpec spec = joint_spec(c);
  o.T_L_S = T_L_S(spec);
  o.protrusion_mm = spec.protrusion_mm;
  o.leg.radius_mm = c.leg_radius_mm;
  o.leg.edge_mm = c.edge_mm;
  o.leg.seed = 11;
  o.stub.radius_mm = c.stub_radius_mm;
  o.stub.edge_mm = c.edge_mm;
  o.stub.seed = 12;
  o.leg_margin_mm = 20.0;
  o.truth_points = 720;
  return o;
}

// Largest distance of a facet of the generated triangulation from its cylinder: R (1 - cos(column step / 2)).
inline double facet_sagitta(const TubeOptions& tube) {
  const TubeGrid grid = tube_grid(tube);
  return tube.radius_mm * (1.0 - std::cos(0.5 * grid.column_step_rad));
}

}  // namespace conform::test
