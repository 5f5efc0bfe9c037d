// `conform generate eroded`: a synthetic eroded turbine-blade surface with craters, as grid files with the reference
// grid and the ground-truth rims beside it (pipelines/generate/generate_eroded.h).

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "number_list.h"
#include "conform/core/error.h"
#include "conform/pipelines/generate/generate_eroded_json.h"
#include "terminal.h"

namespace conform::app {
namespace {

// "X,Y,RADIUS,DEPTH[,INNER[,LIP,LIP_WIDTH]]" -> a crater; conform::Error naming the flag otherwise.
Crater parse_crater(const std::string& text) {
  const std::size_t n = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
  const std::string shape = "X_MM,Y_MM,RADIUS_MM,DEPTH_MM[,INNER_RADIUS_MM[,LIP_MM,LIP_WIDTH_MM]]";
  return eroded_crater(parse_numbers(text, n == 5 || n == 7 ? n : 4, "--crater", shape));
}

Bump parse_bump(const std::string& text) {
  return eroded_bump(parse_numbers(text, 4, "--bump", "X_MM,Y_MM,RADIUS_MM,HEIGHT_MM"));
}

class GenerateErodedCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--out", out_, "Eroded grid CSV to write (row,col,x_mm,y_mm,z_mm); the reference grid goes to "
                                "<name>.reference.csv, the rims to <name>.rims.csv; required")
        ->required();
    c.add_option("--rows", o_.rows, "Grid rows (along y)");
    c.add_option("--cols", o_.cols, "Grid columns (along x)");
    c.add_option("--length", o_.length_mm, "Extent along x (chord), mm");
    c.add_option("--width", o_.width_mm, "Extent along y (span), mm");
    c.add_option("--chord-radius", o_.chord_radius_mm, "Curvature radius along x, mm");
    c.add_option("--span-radius", o_.span_radius_mm, "Curvature radius along y, mm");
    c.add_option("--twist", o_.twist_per_mm, "Twist: z += twist * x * y, 1/mm");
    c.add_option("--crater", craters_,
                 "Crater X_MM,Y_MM,RADIUS_MM,DEPTH_MM [,INNER_RADIUS_MM[,LIP_MM,LIP_WIDTH_MM]] (repeatable; inner radius > 0: "
                 "ring-shaped; a raised lip beyond the rim); without it one at 0,0 of radius 15 mm, depth 2 mm");
    c.add_option("--bump", bumps_, "Raised bump X_MM,Y_MM,RADIUS_MM,HEIGHT_MM (repeatable)");
    c.add_option("--reference-offset", o_.reference_offset_mm, "Reference grid moved along +z (registration error), mm");
    c.add_option("--reference-tilt-deg", o_.reference_tilt_deg, "Reference grid tilted about y, degrees");
    c.add_option("--noise", o_.noise_mm, "Noise of the eroded grid along z (1 sigma), mm");
    c.add_option("--seed", seed_, "Seed of the noise");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  int run() override {
    GenerateErodedOptions options;
    options.eroded = o_;
    options.eroded.seed = seed_;
    if (!craters_.empty()) {
      options.eroded.craters.clear();
      for (const std::string& text : craters_) options.eroded.craters.push_back(parse_crater(text));
    }
    for (const std::string& text : bumps_) options.eroded.bumps.push_back(parse_bump(text));
    options.out_path = out_;
    const GenerateErodedResult r = run_generate_eroded(options);
    if (json_) {
      print_json(generate_eroded_json(options, r));
    } else {
      std::printf("grid        %d x %d points, %g x %g mm\n", r.rows, r.cols, o_.length_mm, o_.width_mm);
      std::printf("craters     %zu, deepest %g mm, noise %g mm\n", r.craters, r.max_depth_mm, options.eroded.noise_mm);
      std::printf("eroded      %s\nreference   %s\nrims        %s\n", r.eroded_path.c_str(), r.reference_path.c_str(),
                  r.rims_path.c_str());
    }
    return 0;
  }

 private:
  ErodedOptions o_;
  std::vector<std::string> craters_;
  std::vector<std::string> bumps_;
  std::uint64_t seed_ = 1;
  std::string out_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(GenerateErodedCommand, "generate eroded",
                "Synthetic eroded blade surface with craters: eroded and reference grids, ground-truth rims")

}  // namespace conform::app
