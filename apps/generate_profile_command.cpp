// `conform generate profile`: a deformed ship profile as a laser sensor measures its edge, with designed features
// and the ground truth of where they lie on the deformed profile (datasets/profile.h).

#include <cmath>
#include <cstdio>
#include <string>

#include "command.h"
#include "number_list.h"
#include "conform/pipelines/generate/generate_profile_json.h"
#include "terminal.h"

namespace conform::app {
namespace {

class GenerateProfileCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description("Synthetic deformed ship profile: measured edge, designed features, ground truth");
    ProfileDeformationOptions& d = o_.deformation;
    c.add_option("--out", out_,
                 "Edge CSV to write; beside it <name>.features.csv, .truth.csv, .truth.json (and .edge2.csv); required")
        ->required();
    c.add_option("--length", d.length_mm, "Profile length along the edge, mm");
    c.add_option("--width", d.width_mm, "Web width (Tx of the second edge), mm");
    c.add_option("--bow", d.bow_in_plane_mm,
                 "In-plane bow: offset of the edge across the web at the middle, mm");
    c.add_option("--bow-asymmetry", d.bow_asymmetry,
                 "a in [-1, 1]: bow 4u(1-u)(1 + a(2u-1)), non-zero makes it a true cubic");
    c.add_option("--bow-out", d.bow_out_of_plane_mm,
                 "Out-of-plane bow along the web normal at the middle, mm");
    c.add_option("--twist-deg", twist_deg_, "Twist about the edge from one end to the other, deg");
    c.add_option("--kink-deg", kink_deg_, "Local in-plane bend of the edge, deg; default 0 (none)");
    c.add_option("--kink-at", d.kink_at_mm, "Ty of the kink's middle, mm");
    c.add_option("--kink-length", d.kink_length_mm, "Length over which the kink bends, mm");
    c.add_option("--spacing", o_.spacing_mm, "Edge sample step along the edge, mm");
    c.add_option("--noise", o_.noise_mm, "Gaussian noise sigma per coordinate, mm");
    c.add_option("--dropouts", o_.dropout_fraction, "Fraction of edge samples dropped at random, [0, 0.5]");
    c.add_flag("--second-edge", o_.second_edge, "Also measure the other edge (Tx = width) into <name>.edge2.csv");
    c.add_option("--holes", o_.holes, "Circles evenly along the profile (Ty = L (k + 1/2) / n)");
    c.add_option("--hole-radius", o_.hole_radius_mm, "Hole radius, mm");
    c.add_option("--hole-tx", o_.hole_tx_mm, "Tx of the hole centres, mm");
    c.add_flag("--marking-line", o_.marking_line, "Add a marking line (polyline M1) at Tx = width / 2");
    c.add_option("--outliers", o_.outliers, "Edge samples moved off the edge (bad readings)");
    c.add_option("--outlier-mm", o_.outlier_mm, "How far the outliers are moved, mm");
    c.add_option("--offset", offset_, "Shop frame: every point moved by x,y,z, mm");
    c.add_flag("--reverse", o_.reversed, "List the edge from the far end (the sensor walked backwards)");
    c.add_option("--seed", o_.seed, "Seed of the noise, the dropouts and the outliers");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  int run() override {
    GenerateProfileRequest request;
    request.scan = o_;
    request.twist_deg = twist_deg_;
    request.kink_deg = kink_deg_;
    const std::vector<double> offset = parse_numbers(offset_, 3, "--offset", "x,y,z");
    request.offset_mm = Eigen::Vector3d(offset[0], offset[1], offset[2]);
    request.out_path = out_;
    const GenerateProfileResult r = run_generate_profile(generate_profile_options(request));
    if (json_) {
      print_json(generate_profile_json(r));
      return 0;
    }
    std::printf("edge       %s (%zu points, %zu dropped)\n", r.edge_path.c_str(), r.edge_points, r.dropped);
    if (!r.second_edge_path.empty()) std::printf("edge 2     %s\n", r.second_edge_path.c_str());
    std::printf("features   %s (%zu features)\n", r.features_path.c_str(), r.features);
    std::printf("truth      %s, %s\n", r.truth_path.c_str(), r.truth_json_path.c_str());
    std::printf("profile    %g x %g mm, bow %g mm (asymmetry %g), out of plane %g mm, twist %g deg, kink %g deg\n",
                o_.deformation.length_mm, o_.deformation.width_mm, o_.deformation.bow_in_plane_mm,
                o_.deformation.bow_asymmetry, o_.deformation.bow_out_of_plane_mm, twist_deg_, kink_deg_);
    std::printf("sensor     every %g mm, noise %g mm, dropouts %g\n", o_.spacing_mm, o_.noise_mm, o_.dropout_fraction);
    return 0;
  }

 private:
  ProfileScanOptions o_;
  std::string offset_ = "0,0,0";
  double twist_deg_ = 0.0;
  double kink_deg_ = 0.0;
  std::string out_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(GenerateProfileCommand, "generate profile",
                "Synthetic deformed ship profile: measured edge, designed features, ground truth")

}  // namespace conform::app
