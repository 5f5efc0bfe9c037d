// `conform pose-error --transform A --transform B`: the rotation angle and translation between two rigid transforms
// (pipelines/pose_error/pose_error.h), for accuracy-evaluation scripts.

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "command.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/units.h"
#include "conform/pipelines/pose_error/pose_error.h"
#include "conform/pipelines/pose_error/pose_error_json.h"
#include "terminal.h"

namespace conform::app {
namespace {

class PoseErrorCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.description(
        "Rotation (deg) and translation (mm) between two rigid transforms A and B: angle of R_A^T R_B, |t_B - t_A|");
    c.add_option("--transform", paths_, "A 4x4 row-major text transform; give exactly two (A, then B)")
        ->required()
        ->allow_extra_args(false);
    c.add_option("--units", units_, "Units of the translations (mm, cm, m, in); results are in mm");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  int run() override {
    if (paths_.size() != 2) {
      throw Error("pose-error compares two transforms: give --transform A --transform B (got " +
                  std::to_string(paths_.size()) + ")");
    }
    PoseErrorOptions options;
    options.path_a = paths_[0];
    options.path_b = paths_[1];
    options.mm_per_unit = millimetres_per_unit(units_);
    const PoseErrorResult r = run_pose_error(options);
    if (json_) {
      print_json(pose_error_json(options, r));
    } else {
      std::printf("rotation     %.9f deg\n", degrees(r.error.rotation_rad));
      std::printf("translation  %.9f mm\n", r.error.translation_mm);
    }
    return 0;
  }

 private:
  std::vector<std::string> paths_;
  std::string units_ = "mm";
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(PoseErrorCommand, "pose-error", "Rotation (deg) and translation (mm) between two rigid transforms")

}  // namespace conform::app
