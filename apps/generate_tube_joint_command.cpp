// `conform generate tube-joint`: a posed leg + stub scan pair with the ground-truth intersection curve
// (pipelines/generate/generate_tube_joint.h), the input `conform tube-joint` expects.

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/pipelines/generate/generate_tube_joint_json.h"
#include "number_list.h"
#include "terminal.h"

namespace conform::app {
namespace {

std::array<double, 4> parse_bump(const std::string& text, const std::string& flag) {
  const std::vector<double> v = parse_numbers(text, 4, flag, "AZ_DEG,Z_MM,HEIGHT_MM,RADIUS_MM");
  return {v[0], v[1], v[2], v[3]};
}

class GenerateTubeJointCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    GenerateTubeJointOptions& job = request_.job;
    c.add_option("--out-leg", job.leg_path, "Leg outer-surface mesh to write (leg frame L), .ply or .stl; required")
        ->required();
    c.add_option("--out-stub", job.stub_path, "Stub inner-surface mesh to write (stub frame S), .ply or .stl; required")
        ->required();
    c.add_option("--out-truth", job.truth_path,
                 "Ground-truth intersection CSV (phi_rad,x_mm,y_mm,z_mm in S) to write; required")
        ->required();
    c.add_option("--pitch-deg", request_.pitch_deg, "Angle between the leg and stub axes, deg, in (0, 90]");
    c.add_option("--offset", job.spec.offset_mm, "Distance between the axes along y_L, mm");
    c.add_option("--protrusion", job.spec.protrusion_mm,
                 "Stub's distal end to the leg axis along the stub axis, mm; default 0 = automatic (" +
                     std::to_string(std::lround(kAutoStubClearanceMm)) + " mm clear)");
    c.add_option("--leg-radius", job.joint.leg.radius_mm, "Leg outer radius, mm");
    c.add_option("--stub-radius", job.stub_outer_radius_mm, "Stub outer radius, mm");
    c.add_option("--wall", job.wall_mm, "Stub wall thickness (scanned inside: radius - wall), mm");
    c.add_option("--edge", request_.edge_mm, "Mesh edge length of both scans, mm");
    c.add_option("--leg-vertices", job.joint.leg.vertex_count, "Leg: about N vertices instead of --edge");
    c.add_option("--stub-vertices", job.joint.stub.vertex_count, "Stub: about N vertices instead of --edge");
    c.add_option("--ovality-pct", request_.ovality_pct,
                 "Ovality of both tubes, D_max - D_min in % of D; default 0 (the issue's case: 1)");
    c.add_option("--peaking", request_.peaking_mm, "Peaking at both seam welds, radial mm");
    c.add_option("--leg-seam-deg", request_.leg_seam_deg, "Leg seam azimuth (from x_L), deg");
    c.add_option("--stub-seam-deg", request_.stub_seam_deg, "Stub seam azimuth (from x_S, the toe), deg");
    c.add_option("--seam-width", request_.seam_width_mm, "Full width of the peaking ridge, arc mm");
    c.add_option("--leg-bump", leg_bumps_, "AZ_DEG,Z_L_MM,HEIGHT_MM,RADIUS_MM: a bump on the leg; repeatable");
    c.add_option("--stub-bump", stub_bumps_, "AZ_DEG,Z_S_MM,HEIGHT_MM,RADIUS_MM: a bump on the stub; repeatable");
    c.add_option("--noise", request_.noise_mm, "Gaussian noise along the normal, sigma, mm");
    c.add_option("--leg-arc-deg", request_.leg_arc_deg, "Leg azimuth span, deg; default 0 = a patch around the joint");
    c.add_option("--stub-length", job.joint.stub_length_mm,
                 "Stub length from its distal end, mm; default 0 = automatic (its end inside the leg)");
    c.add_option("--truth-points", job.joint.truth_points, "Ground-truth samples (equal stub azimuth)");
    c.add_option("--seed", request_.seed, "Seed of the noise (leg: seed, stub: seed + 1)");
    c.add_flag("--ascii", request_.ascii, "Write ascii .ply/.stl");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_outputs({request_.job.leg_path, request_.job.stub_path, request_.job.truth_path});
  }

  int run() override {
    for (const std::string& text : leg_bumps_) request_.leg_bumps.push_back(parse_bump(text, "--leg-bump"));
    for (const std::string& text : stub_bumps_) request_.stub_bumps.push_back(parse_bump(text, "--stub-bump"));
    const GenerateTubeJointOptions o = generate_tube_joint_options(request_);
    const GenerateTubeJointResult r = run_generate_tube_joint(o);
    const double pitch_deg = r.spec.pitch_rad / kPi * 180.0;
    if (json_) {
      print_json(generate_tube_joint_json(o, r));
    } else {
      std::printf("leg         %s (%zu faces, %.1f mm long, %.2f deg arc, frame L)\n", o.leg_path.c_str(), r.leg_faces,
                  r.leg_length_mm, r.leg_arc_rad / kPi * 180.0);
      std::printf("stub        %s (%zu faces, inner radius %.3f mm, %.1f mm long, frame S)\n", o.stub_path.c_str(),
                  r.stub_faces, r.stub_inner_radius_mm, r.stub_length_mm);
      std::printf("truth       %s (%zu points)\n", o.truth_path.c_str(), r.truth_points);
      std::printf("joint       --pitch-deg %.17g --offset %.17g --protrusion %.17g\n", pitch_deg, r.spec.offset_mm,
                  r.spec.protrusion_mm);
    }
    return 0;
  }

 private:
  GenerateTubeJointRequest request_;
  std::vector<std::string> leg_bumps_;
  std::vector<std::string> stub_bumps_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(GenerateTubeJointCommand, "generate tube-joint",
                "Synthetic leg + stub scan pair for tube-joint, with the ground-truth intersection curve")

}  // namespace conform::app
