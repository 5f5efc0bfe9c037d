// `conform export`: a job's path CSV as a robot or CNC program, with full tool frames (docs/export.md;
// toolpath/job_paths.h, tool_frames.h, robot_program.h).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "command.h"
#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/transform_io.h"
#include "conform/toolpath/job_paths.h"
#include "conform/toolpath/robot_program.h"
#include "json_values.h"
#include "number_list.h"
#include "terminal.h"

namespace conform::app {
namespace {

constexpr double kPi = 3.141592653589793;

class ExportCommand : public Command {
 public:
  void configure(CLI::App& c) override {
    c.add_option("--path", path_,
                 "Path CSV of a job: tube-joint cut or weld, saddle, sicp trajectory, profile cut, weld-layers; "
                 "required")
        ->required();
    c.add_option("--format", format_, "Program format")
        ->required()
        ->check(CLI::IsMember({"krl", "rapid", "urscript", "fanuc", "val3", "gcode", "csv"}));
    c.add_option("--out", out_,
                 "Program file to write (main file; parts and a .dtx beside it); its stem names the program "
                 "unless --name; required")
        ->required();
    c.add_option("--frame", frame_path_, "T_base_part: 4x4 text transform placing the part in the robot base; "
                                         "default identity");
    c.add_option("--speed-mm-s", options_.speed_mm_s, "Speed along the path, mm/s");
    c.add_option("--approach-speed-mm-s", options_.approach_speed_mm_s, "Speed of approach and retract moves, mm/s");
    c.add_option("--approach-mm", options_.approach_mm,
                 "Approach and retract distance back along the tool axis (-z), mm; 0: none");
    c.add_option("--name", name_, "Program name (letters, digits, _; starts with a letter); default: --out's "
                                          "stem");
    c.add_option("--tool", options_.tool,
                 "Tool name (rapid tool0, krl TOOL_DATA[1], fanuc UT number 1, val3 tTool when empty)");
    c.add_option("--work-object", options_.work_object,
                 "Work object / base (rapid wobj0, krl BASE_DATA[1], fanuc UF number 1, val3 fPart when empty)");
    c.add_option("--max-points", options_.max_points,
                 "Most motion points per file before the program is split into parts (krl, rapid, fanuc); 0: the "
                 "format's limit (krl 2000, rapid 2000, fanuc 1000)");
    c.add_flag("--three-axis", three_axis_, "gcode: positions only (G1 X Y Z), no TRAORI tool vectors");
    c.add_option("--roll-cone-deg", roll_cone_deg_,
                 "Keep the tool x axis within this angle of --preferred-x (turning about z) to avoid wrist flips, "
                 "deg; 0: off");
    c.add_option("--preferred-x", preferred_x_, "Preferred tool x direction in the part frame, x,y,z");
    c.add_flag("--json", json_, "Print one JSON object on stdout instead of text");
  }

  void declare_files(OutputSet& files) override {
    files.add_inputs({path_, frame_path_});
    files.add_output(out_);
  }

  int run() override {
    ToolFrameOptions frame_options;
    frame_options.roll_cone_rad = roll_cone_deg_ / 180.0 * kPi;
    if (!preferred_x_.empty()) frame_options.preferred_x = parse_vector(preferred_x_, "--preferred-x");
    std::string why;
    if (!frame_options.IsValid(&why)) throw Error("export: " + why);
    if (!frame_path_.empty()) options_.T_base_part = read_transform(frame_path_);
    const std::filesystem::path out(out_);
    options_.name = name_.empty() ? out.stem().string() : name_;
    options_.five_axis = !three_axis_;
    options_.source = std::filesystem::path(path_).filename().string();
    if (!options_.IsValid(&why)) {
      throw Error("export: " + why + (name_.empty() ? " (the name is --out's stem; give --name)" : ""));
    }

    const CsvTable table = read_csv(path_);
    ToolFrameFigures figures;
    const ToolPath path = tool_path_from_csv(table, frame_options, &figures);
    const Program program = write_program(path, format_, options_);
    // The main file goes to --out; the others beside it, under their own names.
    std::vector<std::string> written;
    for (std::size_t i = 0; i < program.files.size(); ++i) {
      const std::string target = i == 0 ? out_ : (out.parent_path() / program.files[i].name).string();
      write_file_atomically(target, program.files[i].text);
      written.push_back(target);
    }
    report(path, program, figures, written);
    return 0;
  }

 private:
  Eigen::Vector3d parse_vector(const std::string& text, const char* option) const {
    const std::vector<double> v = parse_numbers(text, 3, option, "x,y,z");
    return {v[0], v[1], v[2]};
  }

  void report(const ToolPath& path, const Program& program, const ToolFrameFigures& f,
              const std::vector<std::string>& written) const {
    const double max_step_deg = f.max_orientation_step_rad / kPi * 180.0;
    if (json_) {
      print_json({{"job", path.job},
                  {"format", format_},
                  {"segments", path.segments.size()},
                  {"frames", path.frames()},
                  {"targets", program.targets},
                  {"parts", program.parts},
                  {"max_orientation_step_deg", max_step_deg},
                  {"max_orientation_step_frame", f.max_step_index},
                  {"parallel_tangents", f.parallel_tangents},
                  {"repeated_points", f.repeated_points},
                  {"roll_limited", f.roll_limited},
                  {"T_base_part", to_json(options_.T_base_part)},
                  {"written", written}});
    } else {
      std::printf("path          %s file, %zu segments, %zu frames\n", path.job.c_str(), path.segments.size(),
                  path.frames());
      std::printf("program       %s, %zu motion points (approach %g mm), %zu part%s\n", format_.c_str(),
                  program.targets, options_.approach_mm, program.parts, program.parts == 1 ? "" : "s");
      std::printf("orientation   largest change between consecutive frames %.4f deg (frame %zu)\n", max_step_deg,
                  f.max_step_index);
      std::printf("degenerate    %zu tangents along the tool axis, %zu repeated points, %zu rolls limited\n",
                  f.parallel_tangents, f.repeated_points, f.roll_limited);
      for (const std::string& w : written) std::printf("wrote         %s\n", w.c_str());
    }
    if (max_step_deg > 30.0) {
      warn("export: warning: the tool turns by " + std::to_string(max_step_deg) + " deg between two consecutive "
           "frames (frame " + std::to_string(f.max_step_index) + "): check for a wrist flip (--roll-cone-deg)");
    }
  }

  std::string path_;
  std::string format_;
  std::string out_;
  std::string frame_path_;
  ProgramOptions options_;
  std::string name_;
  bool three_axis_ = false;
  double roll_cone_deg_ = 0.0;
  std::string preferred_x_;
  bool json_ = false;
};

}  // namespace

CONFORM_COMMAND(ExportCommand, "export",
                "A job's path CSV as a robot or CNC program (KRL, RAPID, URScript, FANUC, VAL3, G-code) with tool "
                "frames")

}  // namespace conform::app
