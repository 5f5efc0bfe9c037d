// `conform export`: a job's path CSV as a robot or CNC program, with full tool frames (docs/export.md;
// robot/job_paths.h, tool_frames.h, robot_program.h).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "command.h"
#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/pipelines/export/export.h"
#include "conform/pipelines/export/export_json.h"
#include "number_list.h"
#include "terminal.h"

namespace conform::app {
namespace {

class ExportCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--path", paths_,
                 "Path CSV of a job: tube-joint cut or weld, saddle, sicp trajectory, profile cut, weld-layers; "
                 "required. Repeat it for several paths in one program, in order (a joint's cut then its weld), "
                 "with a retract and an approach between them")
        ->required();
    c.add_option("--format", format_, "Program format")
        ->required()
        ->check(CLI::IsMember({"krl", "rapid", "urscript", "fanuc", "val3", "gcode", "csv"}));
    c.add_option("--out", out_,
                 "Program file to write (main file; parts and a .dtx beside it); its stem names the program "
                 "unless --name; required")
        ->required();
    c.add_option("--frame", frame_path_,
                 "T_base_part: 4x4 text transform placing the part in the robot base; "
                 "none: identity");
    c.add_option("--speed-mm-s", options_.speed_mm_s, "Speed along the path, mm/s");
    c.add_option("--approach-speed-mm-s", options_.approach_speed_mm_s, "Speed of approach and retract moves, mm/s");
    c.add_option("--approach-mm", options_.approach_mm,
                 "Approach and retract distance back along the tool axis (-z), mm; 0: none");
    c.add_option("--name", name_,
                 "Program name (letters, digits, _; starts with a letter); empty: --out's "
                 "stem");
    c.add_option("--tool", options_.tool,
                 "Tool name (rapid tool0, krl TOOL_DATA[1], fanuc UT number 1, val3 tTool when empty)");
    c.add_option("--work-object", options_.work_object,
                 "Work object / base (rapid wobj0, krl BASE_DATA[1], fanuc UF number 1, val3 fPart when empty)");
    c.add_option("--max-points", options_.max_points,
                 "Most motion points per file before the program is split into parts (krl, rapid, fanuc); 0: the "
                 "format's limit (krl 2000, rapid 2000, fanuc 1000)");
    c.add_option("--blend-mm", options_.blend_mm,
                 "Blend through the interior points of a path, mm (krl C_DIS, rapid zone, urscript r, val3 leave and "
                 "reach; fanuc CNT100; gcode the machine's own); 0: stop at every point")
        ->check(CLI::Range(0.0, 100.0));
    c.add_option("--process-on", options_.process_on,
                 "One line written after the first point of each path is reached (arc on, spindle on, dispenser), "
                 "in the format's own syntax; empty: none");
    c.add_option("--process-off", options_.process_off,
                 "One line written after the last point of each path, before its retract (arc off ...); empty: none");
    c.add_option("--home", home_,
                 "A joint position J1,...,J6 (deg) reached by a joint move before the first path and after the last "
                 "(robot formats; not gcode or csv); empty: none");
    c.add_flag("--three-axis", three_axis_, "gcode: positions only (G1 X Y Z), no TRAORI tool vectors");
    c.add_option("--roll-cone-deg", roll_cone_deg_,
                 "Keep the tool x axis within this angle of --preferred-x (turning about z) to avoid wrist flips, "
                 "deg; 0: off");
    c.add_option("--preferred-x", preferred_x_, "Preferred tool x direction in the part frame, x,y,z");
    c.add_option("--max-jump-ratio", max_jump_ratio_,
                 "A step between consecutive path points longer than this many times the segment's median step (and "
                 "than 1 mm) is refused as a broken row (exit 2); 0: allow any jump");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs(paths_);
    files.add_input(frame_path_);
    files.add_output(out_);
  }

  int run() override {
    ExportJobOptions o;
    o.path_csvs = paths_;
    o.format = format_;
    o.out_path = out_;
    o.frame_path = frame_path_;
    o.frames.roll_cone_rad = roll_cone_deg_ / 180.0 * kPi;
    o.frames.preferred_x = parse_vector(preferred_x_, "--preferred-x");
    if (!home_.empty()) options_.home_deg = parse_numbers(home_, 6, "--home", "J1,J2,J3,J4,J5,J6");
    o.frames.max_jump_ratio = max_jump_ratio_;
    o.program = options_;
    o.program.name = name_;
    o.program.five_axis = !three_axis_;
    check_export_name(o);
    const ExportJobResult result = run_export(o);
    report(o, result);
    return 0;
  }

 private:
  Eigen::Vector3d parse_vector(const std::string& text, const char* option) const {
    const std::vector<double> v = parse_numbers(text, 3, option, "x,y,z");
    return {v[0], v[1], v[2]};
  }

  void report(const ExportJobOptions& o, const ExportJobResult& r) const {
    const ToolFrameFigures& f = r.figures;
    const double max_step_deg = f.max_orientation_step_rad / kPi * 180.0;
    if (json_) {
      print_json(export_json(o, r));
    } else {
      for (const ExportPathFile& file : r.files) {
        std::printf("path          %s: %s file, %zu segments, %zu frames\n", file.path.c_str(), file.job.c_str(),
                    file.segments, file.frames);
      }
      std::printf("program       %s, %zu motion points (approach %g mm), %zu part%s\n", format_.c_str(), r.targets,
                  options_.approach_mm, r.parts, r.parts == 1 ? "" : "s");
      std::printf("orientation   largest change between consecutive frames %.4f deg (frame %zu)\n", max_step_deg,
                  f.max_step_index);
      std::printf("degenerate    %zu tangents along the tool axis, %zu repeated points, %zu rolls limited\n",
                  f.parallel_tangents, f.repeated_points, f.roll_limited);
      for (const std::string& w : r.written) std::printf("wrote         %s\n", w.c_str());
    }
    for (const std::string& w : export_warnings(r)) warn("export: " + w);
  }

  std::vector<std::string> paths_;
  std::string format_;
  std::string out_;
  std::string frame_path_;
  ProgramOptions options_;
  std::string name_;
  bool three_axis_ = false;
  double roll_cone_deg_ = 0.0;
  double max_jump_ratio_ = ToolFrameOptions{}.max_jump_ratio;
  std::string preferred_x_ = "1,0,0";
  std::string home_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(ExportCommand, "export",
                "A job's path CSV as a robot or CNC program (KRL, RAPID, URScript, FANUC, VAL3, G-code) with tool "
                "frames")

}  // namespace conform::app
