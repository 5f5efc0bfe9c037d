#include "conform/robot/robot_program.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <string_view>

#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "program_writers.h"

namespace conform {
namespace {

bool identifier(const std::string& s) {
  if (s.empty() || s.size() > 20 || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// A tool or work-object name goes into program text verbatim: letters, digits and _ [ ] only, so it cannot end a
// statement or a comment.
bool name_text(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '[' || c == ']';
  });
}

bool rigid(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d r = T.linear();
  return T.matrix().allFinite() && (r.transpose() * r - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
         std::abs(r.determinant() - 1.0) < 1e-6;
}

}  // namespace

bool ProgramOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(std::isfinite(speed_mm_s) && speed_mm_s > 0.0)) why << "the speed must be positive; ";
  if (!(std::isfinite(approach_speed_mm_s) && approach_speed_mm_s > 0.0))
    why << "the approach speed must be positive; ";
  if (!(std::isfinite(approach_mm) && approach_mm >= 0.0)) why << "the approach distance must be >= 0; ";
  if (!identifier(name)) {
    why << "the program name '" << name << "' must be 1 to 20 letters, digits or _, starting with a letter; ";
  }
  if (!name_text(tool) || !name_text(work_object)) why << "tool and work-object names: letters, digits, _ [ ] only; ";
  if (!rigid(T_base_part)) why << "T_base_part is not a rigid transform; ";
  if (!(std::isfinite(blend_mm) && blend_mm >= 0.0 && blend_mm <= 100.0)) why << "the blend must be in [0, 100] mm; ";
  if (!home_deg.empty() && (home_deg.size() != 6 || !std::all_of(home_deg.begin(), home_deg.end(), [](double j) {
                              return std::isfinite(j) && std::abs(j) <= 720.0;
                            }))) {
    why << "the home position must be six joint angles within +-720 deg; ";
  }
  for (const std::string* line : {&process_on, &process_off}) {
    if (std::any_of(line->begin(), line->end(), [](char c) { return std::iscntrl(static_cast<unsigned char>(c)); })) {
      why << "a process line may not hold a line break or another control character; ";
    }
  }
  std::string text = why.str();
  if (text.size() >= 2) text.resize(text.size() - 2);
  if (error != nullptr) *error = text;
  return text.empty();
}

const std::vector<std::string>& program_formats() {
  static const std::vector<std::string> formats = {"krl", "rapid", "urscript", "fanuc", "val3", "gcode", "csv"};
  return formats;
}

std::string program_extension(const std::string& format) {
  if (format == "krl") return ".src";
  if (format == "rapid") return ".mod";
  if (format == "urscript") return ".script";
  if (format == "fanuc") return ".ls";
  if (format == "val3") return ".pgx";
  if (format == "gcode") return ".nc";
  if (format == "csv") return ".csv";
  throw Error("export: unknown format '" + format + "' (krl, rapid, urscript, fanuc, val3, gcode, csv)");
}

namespace detail {

bool starts_path(const std::vector<RobotTarget>& targets, std::size_t i) {
  const RobotTarget& t = targets[i];
  return t.kind == MoveKind::kPath &&
         (i == 0 || targets[i - 1].kind != MoveKind::kPath || targets[i - 1].segment != t.segment);
}

bool ends_path(const std::vector<RobotTarget>& targets, std::size_t i) {
  const RobotTarget& t = targets[i];
  return t.kind == MoveKind::kPath &&
         (i + 1 == targets.size() || targets[i + 1].kind != MoveKind::kPath || targets[i + 1].segment != t.segment);
}

bool blends(const std::vector<RobotTarget>& targets, std::size_t i, const ProgramOptions& options) {
  return options.blend_mm > 0.0 && targets[i].kind == MoveKind::kPath && !starts_path(targets, i) &&
         !ends_path(targets, i);
}

}  // namespace detail

std::vector<RobotTarget> plan_targets(const ToolPath& path, const ProgramOptions& options) {
  std::vector<RobotTarget> targets;
  targets.reserve(path.frames() + 2 * path.segments.size());
  const Eigen::Matrix3d r_base_part = options.T_base_part.linear();
  for (std::size_t s = 0; s < path.segments.size(); ++s) {
    const std::vector<ToolFrame>& frames = path.segments[s].frames;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      RobotTarget t;
      t.position_mm = options.T_base_part * frames[i].position;
      t.rotation = r_base_part * frames[i].rotation;
      t.segment = s;
      const Eigen::Vector3d back = -options.approach_mm * t.rotation.col(2);  // -z: away from the work
      if (i == 0 && options.approach_mm > 0.0) {
        RobotTarget a = t;
        a.position_mm += back;
        a.kind = MoveKind::kApproach;
        targets.push_back(a);
      }
      targets.push_back(t);
      if (i + 1 == frames.size() && options.approach_mm > 0.0) {
        RobotTarget r = t;
        r.position_mm += back;
        r.kind = MoveKind::kRetract;
        targets.push_back(r);
      }
    }
  }
  return targets;
}

Program write_program(const ToolPath& path, const std::string& format, const ProgramOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("export: " + why);
  program_extension(format);  // refuses an unknown format
  const std::vector<RobotTarget> targets = plan_targets(path, options);
  if (targets.empty()) throw Error("export: the path has no points");
  if (!options.home_deg.empty() && (format == "gcode" || format == "csv")) {
    throw Error("export: a home joint position (--home) is for robot programs; " + format + " has no robot joints");
  }
  Program program;
  if (format == "krl") program = detail::write_krl(targets, options);
  if (format == "rapid") program = detail::write_rapid(targets, options);
  if (format == "urscript") program = detail::write_urscript(targets, options);
  if (format == "fanuc") program = detail::write_fanuc(targets, options);
  if (format == "val3") program = detail::write_val3(targets, options);
  if (format == "gcode") program = detail::write_gcode(targets, options);
  if (format == "csv") program = detail::write_frames_csv(targets, options);
  program.targets = targets.size();
  return program;
}

namespace detail {

std::string num(double value, int decimals) { return format_fixed(value, decimals); }

std::vector<std::pair<std::size_t, std::size_t>> parts_of(std::size_t count, std::size_t max) {
  std::vector<std::pair<std::size_t, std::size_t>> parts;
  if (max == 0) max = count;
  for (std::size_t begin = 0; begin < count; begin += max) parts.emplace_back(begin, std::min(count, begin + max));
  return parts;
}

std::string tool_or(const ProgramOptions& options, const std::string& fallback) {
  return options.tool.empty() ? fallback : options.tool;
}

std::string work_object_or(const ProgramOptions& options, const std::string& fallback) {
  return options.work_object.empty() ? fallback : options.work_object;
}

std::string provenance(const ProgramOptions& options, std::size_t targets) {
  std::string source = options.source.empty() ? std::string("a path") : options.source;
  // Into a comment: nothing that could end it or the line.
  for (char& c : source) {
    if (c < 0x20 || c > 0x7e || std::string_view("\"';!()<>&").find(c) != std::string_view::npos) c = '_';
  }
  // Nor "--", which would end VAL3's XML comment.
  for (std::size_t at; (at = source.find("--")) != std::string::npos;) source[at + 1] = '_';
  return "conform export of " + source + ": " + std::to_string(targets) + " points, mm, base frame";
}

}  // namespace detail
}  // namespace conform
