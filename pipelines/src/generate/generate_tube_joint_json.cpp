#include "conform/pipelines/generate/generate_tube_joint_json.h"

#include "conform/core/constants.h"

namespace conform {
GenerateTubeJointOptions generate_tube_joint_options(const GenerateTubeJointRequest& r) {
  GenerateTubeJointOptions o = r.job;
  o.spec.pitch_rad = radians(r.pitch_deg);
  o.encoding = r.ascii ? Encoding::kAscii : Encoding::kBinary;
  o.joint.leg_arc_rad = radians(r.leg_arc_deg);
  const double stub_inner = o.stub_outer_radius_mm - o.wall_mm;
  for (TubeOptions* t : {&o.joint.leg, &o.joint.stub}) {
    t->edge_mm = r.edge_mm;
    t->noise_mm = r.noise_mm;
    t->seam_height_mm = r.peaking_mm;
    t->seam_width_mm = r.seam_width_mm;
  }
  o.joint.leg.ovality_mm = r.ovality_pct / 100.0 * 2.0 * o.joint.leg.radius_mm / 4.0;
  o.joint.stub.ovality_mm = r.ovality_pct / 100.0 * 2.0 * stub_inner / 4.0;
  o.joint.leg.seam_azimuth_rad = radians(r.leg_seam_deg);
  o.joint.stub.seam_azimuth_rad = radians(r.stub_seam_deg);
  o.joint.leg.seed = r.seed;
  o.joint.stub.seed = r.seed + 1;
  for (const std::array<double, 4>& v : r.leg_bumps) o.joint.leg.bumps.push_back({radians(v[0]), v[1], v[2], v[3]});
  for (const std::array<double, 4>& v : r.stub_bumps) o.joint.stub.bumps.push_back({radians(v[0]), v[1], v[2], v[3]});
  return o;
}

nlohmann::json generate_tube_joint_json(const GenerateTubeJointOptions& o, const GenerateTubeJointResult& r) {
  return {{"leg", o.leg_path},
          {"stub", o.stub_path},
          {"truth", o.truth_path},
          {"pitch_deg", r.spec.pitch_rad / kPi * 180.0},
          {"offset_mm", r.spec.offset_mm},
          {"protrusion_mm", r.spec.protrusion_mm},
          {"stub_inner_radius_mm", r.stub_inner_radius_mm},
          {"leg_faces", r.leg_faces},
          {"stub_faces", r.stub_faces},
          {"leg_length_mm", r.leg_length_mm},
          {"leg_arc_deg", r.leg_arc_rad / kPi * 180.0},
          {"stub_length_mm", r.stub_length_mm},
          {"truth_points", r.truth_points}};
}

}  // namespace conform
