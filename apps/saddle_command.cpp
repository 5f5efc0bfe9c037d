// `conform saddle`: the saddle-shaped weld path of a pipe on a cylinder, interpolated at equal angles or at constant
// torch speed, with the torch pose angle (Xue et al. 2018, generalised to any pitch and offset).

#include <cstdio>
#include <string>

#include "command.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/pipelines/saddle/saddle.h"
#include "conform/pipelines/saddle/saddle_json.h"
#include "conform/pipelines/saddle/saddle_report.h"
#include "report_option.h"
#include "terminal.h"

namespace conform::app {
namespace {

class SaddleCommand : public Command {
 public:
  void configure(CLI::App& command) override {
    command.add_option("--R", request_.leg_radius_mm, "Cylinder (leg) radius R, mm; required")->required();
    command
        .add_option("--r", request_.pipe_radius_mm, "Pipe radius r, mm, 0 < r <= R (r = R: equal diameters); required")
        ->required();
    command.add_option("--pitch-deg", request_.pitch_deg,
                       "Angle between the pipe axis and the cylinder axis, deg, in [1, 90]; 90 is the paper's "
                       "right-angle joint");
    command.add_option("--offset", request_.offset_mm,
                       "Distance between the two axes, mm, |offset| + r <= R; 0: the axes intersect");
    command
        .add_option("--right-angle-pose-deg,--start-pose-deg", request_.right_angle_pose_deg,
                    "Torch pose angle where the two surfaces meet at a right angle (phi of Eq. 12: the pose is 90 - "
                    "dihedral + phi; the pose at theta = 0 only for pitch 90, offset 0; Table 1 uses 45), deg, in "
                    "(-180, 180]; required")
        ->required();
    CLI::Option* step = command.add_option(
        "--step-deg", step_deg_, "Equal-angle interpolation: rotation per step, deg, in (0, 180); no default");
    CLI::Option* speed = command.add_option(
        "--speed", speed_mm_per_s_, "Constant-speed interpolation: torch speed along the seam, mm/s; no default");
    CLI::Option* period = command.add_option(
        "--period", period_s_, "Constant-speed interpolation: interpolation period, s (e.g. 0.004); no default");
    step->excludes(speed)->excludes(period);
    speed->needs(period);
    period->needs(speed);
    command.add_option("--out", out_path_, "CSV to write: i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm");
    add_report_option(command, report_);
    command.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
    step_ = step;
    speed_ = speed;
  }

  void declare_files(OutputSet& files) override { files.add_outputs({out_path_, report_}); }

  int run() override {
    if (step_->count() > 0) request_.step_deg = step_deg_;
    if (speed_->count() > 0) {
      request_.speed_mm_per_s = speed_mm_per_s_;
      request_.period_s = period_s_;
    }
    request_.out_path = out_path_;
    const SaddleJobOptions options = saddle_job_options(request_);
    const SaddleJobResult result = run_saddle(options);
    if (json_) {
      print_json(saddle_json(request_, result));
    } else {
      print_text(result);
    }
    if (!report_.empty()) {
      html::Page page = saddle_report(request_, options, result);
      page.date = report_date();
      write_report(report_, page);
    }
    if (!result.saddle.converged) {
      warn("saddle: " + result.saddle.termination + "; no file written");
      return 1;
    }
    return 0;
  }

 private:
  void print_text(const SaddleJobResult& job) const {
    const SaddleResult& s = job.saddle;
    std::printf("seam          R %g mm, r %g mm, pitch %g deg, offset %g mm\n", request_.leg_radius_mm,
                request_.pipe_radius_mm, request_.pitch_deg, request_.offset_mm);
    if (s.rule == SaddleStepRule::kEqualAngle) {
      std::printf("interpolation %s, %g deg per step, pose %g deg at a right-angle dihedral\n", to_string(s.rule),
                  step_deg_, request_.right_angle_pose_deg);
    } else {
      std::printf("interpolation %s, %g mm/s x %g s = %g mm per period, pose %g deg at a right-angle dihedral\n",
                  to_string(s.rule), speed_mm_per_s_, period_s_, speed_mm_per_s_ * period_s_,
                  request_.right_angle_pose_deg);
    }
    std::printf("points        %zu (%zu full steps, last step %.6f mm%s)\n", s.points.size(), s.full_steps,
                s.last_step_mm, s.last_step_partial ? ", shortened to land on 360 deg" : "");
    if (s.corner_steps > 0) std::printf("corners       %zu steps shortened to end on a corner\n", s.corner_steps);
    std::printf("step mm       min %.6f  mean %.6f  max %.6f\n", s.step_mm_min, s.step_mm_mean, s.step_mm_max);
    std::printf("speed ripple  %.6f %%\n", s.speed_ripple_pct);
    std::printf("length mm     path %.6f  seam %.6f\n", s.path_length_mm, s.curve_length_mm);
    std::printf("pose deg      min %.4f  max %.4f\n", degrees(s.pose_rad_min), degrees(s.pose_rad_max));
    std::printf("residual mm   pipe %.3g  cylinder %.3g\n", s.max_pipe_residual_mm, s.max_leg_residual_mm);
    std::printf("out           %s\n", job.out_path.empty() ? "(none)" : job.out_path.c_str());
  }

  SaddleRequest request_;
  double step_deg_ = 0.0;
  double speed_mm_per_s_ = 0.0;
  double period_s_ = 0.0;
  std::string out_path_;
  std::string report_;
  bool json_ = false;
  CLI::Option* step_ = nullptr;
  CLI::Option* speed_ = nullptr;
};

}  // namespace

CONFORM_COMMAND(SaddleCommand, "saddle",
                "Saddle weld path of a pipe on a cylinder with torch pose, equal-angle or constant speed (Xue 2018)")

}  // namespace conform::app
