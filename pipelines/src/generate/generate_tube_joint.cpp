#include "conform/pipelines/generate/generate_tube_joint.h"

#include <cmath>
#include <cstdio>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/output_set.h"

namespace conform {
namespace {

bool mesh_extension(const std::string& path) {
  const std::string e = file_extension(path);
  return e == ".ply" || e == ".stl";
}

}  // namespace

bool GenerateTubeJointOptions::IsValid(std::string* error) const {
  std::string why;
  TubeJointSpec checked = spec;
  if (!(checked.protrusion_mm > 0.0)) checked.protrusion_mm = 1.0;
  if (leg_path.empty() || stub_path.empty() || truth_path.empty()) {
    why = "give the three outputs: the leg mesh, the stub mesh (.ply or .stl) and the truth (.csv)";
  } else if (!mesh_extension(leg_path)) {
    why = leg_path + ": the leg mesh is written as .ply or .stl";
  } else if (!mesh_extension(stub_path)) {
    why = stub_path + ": the stub mesh is written as .ply or .stl";
  } else if (file_extension(truth_path) != ".csv") {
    why = truth_path + ": the truth is written as .csv";
  } else if (!checked.IsValid(&why)) {
    why = "joint: " + why;
  } else if (!(std::isfinite(stub_outer_radius_mm) && std::isfinite(wall_mm) && wall_mm >= 0.0 &&
               stub_outer_radius_mm - wall_mm > 0.0)) {
    why = "the stub's outer radius must exceed its wall (both finite, mm)";
  } else if (!(joint.leg.radius_mm > stub_outer_radius_mm - wall_mm + std::abs(spec.offset_mm))) {
    why = "the leg radius must exceed the stub's inner radius plus the offset, or the stub misses the leg";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

double automatic_protrusion(double pitch_rad, double leg_radius_mm, double stub_radius_mm, double clearance_mm) {
  const Eigen::Vector2d cs = pitch_cos_sin(pitch_rad);
  return (leg_radius_mm + stub_radius_mm * cs.x()) / cs.y() + clearance_mm;
}

std::string tube_joint_truth_csv(const TubeJointTruth& truth) {
  CsvWriter csv({"phi_rad", "x_mm", "y_mm", "z_mm"}, 9);
  for (std::size_t i = 0; i < truth.points.size(); ++i) {
    csv.cell(truth.phi_rad[i]).cell(truth.points[i].x()).cell(truth.points[i].y()).cell(truth.points[i].z());
    csv.end_row();
  }
  return csv.text();
}

GenerateTubeJointResult run_generate_tube_joint(const GenerateTubeJointOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("generate tube-joint: " + why);
  GenerateTubeJointResult result;
  result.spec = options.spec;
  if (!(result.spec.protrusion_mm > 0.0)) {
    result.spec.protrusion_mm = automatic_protrusion(options.spec.pitch_rad, options.joint.leg.radius_mm,
                                                     options.stub_outer_radius_mm, kAutoStubClearanceMm);
  }
  result.stub_inner_radius_mm = options.stub_outer_radius_mm - options.wall_mm;
  TubeJointOptions joint = options.joint;
  joint.T_L_S = T_L_S(result.spec);
  joint.protrusion_mm = result.spec.protrusion_mm;
  joint.stub.radius_mm = result.stub_inner_radius_mm;
  const TubeJointScans scans = generate_tube_joint(joint);
  result.leg_faces = scans.leg_L.faces.size();
  result.stub_faces = scans.stub_S.faces.size();
  result.leg_length_mm = scans.truth.leg.length_mm;
  result.leg_arc_rad = scans.truth.leg.arc_rad;
  result.stub_length_mm = scans.truth.stub.length_mm;
  result.truth_points = scans.truth.points.size();
  WriteOptions write;
  write.encoding = options.encoding;
  OutputSet outputs;  // both scans and their truth, or none
  write_mesh(options.leg_path, scans.leg_L, write);
  write_mesh(options.stub_path, scans.stub_S, write);
  write_file_atomically(options.truth_path, tube_joint_truth_csv(scans.truth));
  outputs.commit();
  return result;
}

}  // namespace conform
