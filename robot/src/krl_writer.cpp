// KUKA KRL (.src): LIN {X, Y, Z, A, B, C} in mm and degrees, A B C = rotations about z, y', x'' (KSS manual, "Frame").

#include <string>

#include "conform/robot/robot_angles.h"
#include "program_writers.h"

namespace conform::detail {
namespace {

constexpr std::size_t kKrlMaxPoints = 2000;

std::string speed_line(double mm_s) { return "$VEL.CP = " + num(mm_s / 1000.0, 6) + "  ; m/s\n"; }

}  // namespace

Program write_krl(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  std::vector<std::string> moves;
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RobotTarget& t = targets[i];
    abc = euler_zyx_deg(t.rotation, i == 0 ? nullptr : &abc);
    std::string line;
    if (i == 0 || targets[i - 1].kind != t.kind) {
      line += speed_line(t.kind == MoveKind::kPath ? options.speed_mm_s : options.approach_speed_mm_s);
    }
    // The approach point is reached by a joint move (the robot comes from anywhere), the path and the retract by
    // straight lines.
    line += std::string(t.kind == MoveKind::kApproach ? "PTP" : "LIN") + " {X " + num(t.position_mm.x(), 6) + ", Y " +
            num(t.position_mm.y(), 6) + ", Z " + num(t.position_mm.z(), 6) + ", A " + num(abc(0), 9) + ", B " +
            num(abc(1), 9) + ", C " + num(abc(2), 9) + "}" + (blends(targets, i, options) ? " C_DIS" : "") + "\n";
    if (starts_path(targets, i) && !options.process_on.empty()) line += options.process_on + "\n";
    if (ends_path(targets, i) && !options.process_off.empty()) line += options.process_off + "\n";
    moves.push_back(line);
  }
  const auto parts = parts_of(targets.size(), options.max_points == 0 ? kKrlMaxPoints : options.max_points);
  Program program;
  program.parts = parts.size();
  std::string main = "&ACCESS RVP\n&REL 1\nDEF " + options.name + "( )\n; " + provenance(options, targets.size()) +
                     "\n; A B C in degrees, Z-Y'-X''\n";
  main += "$TOOL = " + tool_or(options, "TOOL_DATA[1]") + "\n$BASE = " + work_object_or(options, "BASE_DATA[1]") +
          "\n$ADVANCE = 3\n$APO.CDIS = " + num(options.blend_mm, 3) + "\n$ORI_TYPE = #VAR\n";
  std::string home;
  if (!options.home_deg.empty()) {
    home = "PTP {A1 " + num(options.home_deg[0], 6);
    for (int k = 1; k < 6; ++k) home += ", A" + std::to_string(k + 1) + " " + num(options.home_deg[k], 6);
    home += "}  ; home\n";
  }
  main += home;
  if (parts.size() == 1) {
    for (const std::string& m : moves) main += m;
  } else {
    for (std::size_t k = 0; k < parts.size(); ++k) main += options.name + "_" + std::to_string(k + 1) + "( )\n";
  }
  main += home + "END\n";
  program.files.push_back({options.name + ".src", main});
  if (parts.size() == 1) return program;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string name = options.name + "_" + std::to_string(k + 1);
    std::string text = "&ACCESS RVP\n&REL 1\nDEF " + name + "( )\n; part " + std::to_string(k + 1) + " of " +
                       std::to_string(parts.size()) + "\n";
    // Each part sets its speed again: it may start on a path move.
    text +=
        speed_line(targets[parts[k].first].kind == MoveKind::kPath ? options.speed_mm_s : options.approach_speed_mm_s);
    for (std::size_t i = parts[k].first; i < parts[k].second; ++i) text += moves[i];
    text += "END\n";
    program.files.push_back({name + ".src", text});
  }
  return program;
}

}  // namespace conform::detail
