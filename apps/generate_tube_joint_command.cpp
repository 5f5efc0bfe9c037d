// `conform generate tube-joint`: a posed leg + stub scan pair with the ground-truth intersection curve
// (pipelines/generate_tube_joint.h), the input `conform tube-joint` expects.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "number_list.h"
#include "conform/core/error.h"
#include "conform/pipelines/generate_tube_joint.h"
#include "terminal.h"

namespace conform::app {
namespace {

constexpr double kPi = 3.141592653589793;
double radians(double deg) { return deg / 180.0 * kPi; }

std::vector<double> parse_bump(const std::string& text, const std::string& flag) {
  return parse_numbers(text, 4, flag, "AZ_DEG,Z_MM,HEIGHT_MM,RADIUS_MM");
}

class GenerateTubeJointCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    o_.joint.leg.radius_mm = 1000.0;
    c.add_option("--out-leg", o_.leg_path, "Leg outer-surface mesh to write (leg frame L), .ply or .stl; required")
        ->required();
    c.add_option("--out-stub", o_.stub_path, "Stub inner-surface mesh to write (stub frame S), .ply or .stl; required")
        ->required();
    c.add_option("--out-truth", o_.truth_path,
                 "Ground-truth intersection CSV (phi_rad,x_mm,y_mm,z_mm in S) to write; required")
        ->required();
    c.add_option("--pitch-deg", pitch_deg_, "Angle between the leg and stub axes, deg, in (0, 90]");
    c.add_option("--offset", o_.spec.offset_mm, "Distance between the axes along y_L, mm");
    c.add_option("--protrusion", o_.spec.protrusion_mm,
                 "Stub's distal end to the leg axis along the stub axis, mm; default 0 = automatic (100 mm clear)");
    c.add_option("--leg-radius", o_.joint.leg.radius_mm, "Leg outer radius, mm");
    c.add_option("--stub-radius", o_.stub_outer_radius_mm, "Stub outer radius, mm");
    c.add_option("--wall", o_.wall_mm, "Stub wall thickness (scanned inside: radius - wall), mm");
    c.add_option("--edge", edge_mm_, "Mesh edge length of both scans, mm");
    c.add_option("--leg-vertices", o_.joint.leg.vertex_count, "Leg: about N vertices instead of --edge");
    c.add_option("--stub-vertices", o_.joint.stub.vertex_count, "Stub: about N vertices instead of --edge");
    c.add_option("--ovality-pct", ovality_pct_,
                 "Ovality of both tubes, D_max - D_min in % of D; default 0 (the issue's case: 1)");
    c.add_option("--peaking", peaking_mm_, "Peaking at both seam welds, radial mm");
    c.add_option("--leg-seam-deg", leg_seam_deg_, "Leg seam azimuth (from x_L), deg");
    c.add_option("--stub-seam-deg", stub_seam_deg_, "Stub seam azimuth (from x_S, the toe), deg");
    c.add_option("--seam-width", seam_width_mm_, "Full width of the peaking ridge, arc mm");
    c.add_option("--leg-bump", leg_bumps_, "AZ_DEG,Z_L_MM,HEIGHT_MM,RADIUS_MM: a bump on the leg; repeatable");
    c.add_option("--stub-bump", stub_bumps_, "AZ_DEG,Z_S_MM,HEIGHT_MM,RADIUS_MM: a bump on the stub; repeatable");
    c.add_option("--noise", noise_mm_, "Gaussian noise along the normal, sigma, mm");
    c.add_option("--leg-arc-deg", leg_arc_deg_, "Leg azimuth span, deg; default 0 = a patch around the joint");
    c.add_option("--stub-length", o_.joint.stub_length_mm,
                 "Stub length from its distal end, mm; default 0 = automatic (its end inside the leg)");
    c.add_option("--truth-points", o_.joint.truth_points, "Ground-truth samples (equal stub azimuth)");
    c.add_option("--seed", seed_, "Seed of the noise (leg: seed, stub: seed + 1)");
    c.add_flag("--ascii", ascii_, "Write ascii .ply/.stl");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override { files.add_outputs({o_.leg_path, o_.stub_path, o_.truth_path}); }

  int run() override {
    GenerateTubeJointOptions o = o_;
    o.spec.pitch_rad = radians(pitch_deg_);
    o.encoding = ascii_ ? Encoding::kAscii : Encoding::kBinary;
    o.joint.leg_arc_rad = radians(leg_arc_deg_);
    const double stub_inner = o.stub_outer_radius_mm - o.wall_mm;
    for (TubeOptions* t : {&o.joint.leg, &o.joint.stub}) {
      t->edge_mm = edge_mm_;
      t->noise_mm = noise_mm_;
      t->seam_height_mm = peaking_mm_;
      t->seam_width_mm = seam_width_mm_;
    }
    o.joint.leg.ovality_mm = ovality_pct_ / 100.0 * 2.0 * o.joint.leg.radius_mm / 4.0;
    o.joint.stub.ovality_mm = ovality_pct_ / 100.0 * 2.0 * stub_inner / 4.0;
    o.joint.leg.seam_azimuth_rad = radians(leg_seam_deg_);
    o.joint.stub.seam_azimuth_rad = radians(stub_seam_deg_);
    o.joint.leg.seed = seed_;
    o.joint.stub.seed = seed_ + 1;
    for (const std::string& text : leg_bumps_) {
      const std::vector<double> v = parse_bump(text, "--leg-bump");
      o.joint.leg.bumps.push_back({radians(v[0]), v[1], v[2], v[3]});
    }
    for (const std::string& text : stub_bumps_) {
      const std::vector<double> v = parse_bump(text, "--stub-bump");
      o.joint.stub.bumps.push_back({radians(v[0]), v[1], v[2], v[3]});
    }
    const GenerateTubeJointResult r = run_generate_tube_joint(o);
    const double pitch_deg = r.spec.pitch_rad / kPi * 180.0;
    if (json_) {
      print_json({{"leg", o.leg_path},
                  {"stub", o.stub_path},
                  {"truth", o.truth_path},
                  {"pitch_deg", pitch_deg},
                  {"offset_mm", r.spec.offset_mm},
                  {"protrusion_mm", r.spec.protrusion_mm},
                  {"stub_inner_radius_mm", r.stub_inner_radius_mm},
                  {"leg_faces", r.leg_faces},
                  {"stub_faces", r.stub_faces},
                  {"leg_length_mm", r.leg_length_mm},
                  {"leg_arc_deg", r.leg_arc_rad / kPi * 180.0},
                  {"stub_length_mm", r.stub_length_mm},
                  {"truth_points", r.truth_points}});
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
  GenerateTubeJointOptions o_;
  double pitch_deg_ = 90.0;
  double edge_mm_ = 5.0;
  double ovality_pct_ = 0.0;
  double peaking_mm_ = 0.0;
  double leg_seam_deg_ = 15.0;
  double stub_seam_deg_ = 100.0;
  double seam_width_mm_ = 150.0;
  double noise_mm_ = 0.0;
  double leg_arc_deg_ = 0.0;
  std::vector<std::string> leg_bumps_;
  std::vector<std::string> stub_bumps_;
  std::uint64_t seed_ = 1;
  bool ascii_ = false;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(GenerateTubeJointCommand, "generate tube-joint",
                "Synthetic leg + stub scan pair for tube-joint, with the ground-truth intersection curve")

}  // namespace conform::app
