// ABB RAPID (.mod): robtargets [[x,y,z],[q1,q2,q3,q4],[cf1,cf4,cf6,cfx],[9E9 x 6]], q1 the scalar part of the unit
// quaternion (RAPID reference manual, "orient"), MoveL.

#include <string>

#include "conform/robot/robot_angles.h"
#include "program_writers.h"

namespace conform::detail {
namespace {

constexpr std::size_t kRapidMaxPoints = 2000;

std::string speeddata(const char* name, double mm_s) {
  return "  LOCAL CONST speeddata " + std::string(name) + " := [" + num(mm_s, 3) + ", 500, 5000, 1000];\n";
}

std::string module(const std::string& name, const std::string& body, const std::vector<std::string>& targets,
                   const ProgramOptions& options) {
  std::string text = "MODULE " + name + "\n  ! " + provenance(options, targets.size()) + "\n";
  text += speeddata("vPath", options.speed_mm_s) + speeddata("vApproach", options.approach_speed_mm_s);
  if (!options.home_deg.empty()) {
    text += "  LOCAL CONST jointtarget jHome := [[" + num(options.home_deg[0], 6);
    for (int k = 1; k < 6; ++k) text += "," + num(options.home_deg[k], 6);
    text += "],[9E9,9E9,9E9,9E9,9E9,9E9]];\n";
  }
  if (options.blend_mm > 0.0) {
    // z1's proportions (RAPID reference manual, "zonedata"), scaled to the blend distance.
    const double b = options.blend_mm;
    text += "  LOCAL CONST zonedata zPath := [FALSE," + num(b, 3) + "," + num(b, 3) + "," + num(b, 3) + "," +
            num(0.1 * b, 4) + "," + num(b, 3) + "," + num(0.1 * b, 4) + "];\n";
  }
  for (const std::string& t : targets) text += t;
  return text + body + "ENDMODULE\n";
}

}  // namespace

Program write_rapid(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  const std::string tool = tool_or(options, "tool0");
  const std::string wobj = work_object_or(options, "wobj0");
  const std::string home = options.home_deg.empty()
                               ? ""
                               : "    MoveAbsJ jHome\\NoEOffs, vApproach, fine, " + tool + " \\WObj:=" + wobj + ";\n";
  const auto parts = parts_of(targets.size(), options.max_points == 0 ? kRapidMaxPoints : options.max_points);
  Program program;
  program.parts = parts.size();
  Eigen::Vector4d q = Eigen::Vector4d::Zero();
  std::vector<std::string> data(targets.size());
  std::vector<std::string> moves(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RobotTarget& t = targets[i];
    q = quaternion_wxyz(t.rotation, i == 0 ? nullptr : &q);
    const std::string name = "p" + std::to_string(i + 1);
    data[i] = "  LOCAL CONST robtarget " + name + " := [[" + num(t.position_mm.x(), 6) + "," +
              num(t.position_mm.y(), 6) + "," + num(t.position_mm.z(), 6) + "],[" + num(q(0), 12) + "," +
              num(q(1), 12) + "," + num(q(2), 12) + "," + num(q(3), 12) + "],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n";
    const bool path = t.kind == MoveKind::kPath;
    // The approach point by a joint move (the robot comes from anywhere), the path and the retract linear.
    moves[i] = std::string(t.kind == MoveKind::kApproach ? "    MoveJ " : "    MoveL ") + name + ", " +
               (path ? "vPath" : "vApproach") + ", " + (blends(targets, i, options) ? "zPath" : "fine") + ", " + tool +
               " \\WObj:=" + wobj + ";\n";
    if (starts_path(targets, i) && !options.process_on.empty()) moves[i] += "    " + options.process_on + "\n";
    if (ends_path(targets, i) && !options.process_off.empty()) moves[i] += "    " + options.process_off + "\n";
  }
  if (parts.size() == 1) {
    std::string body = "  PROC main()\n    ConfL \\Off;\n" + home;
    for (const std::string& m : moves) body += m;
    body += home + "  ENDPROC\n";
    program.files.push_back({options.name + ".mod", module(options.name, body, data, options)});
    return program;
  }
  std::string body = "  PROC main()\n    ConfL \\Off;\n" + home;
  for (std::size_t k = 0; k < parts.size(); ++k)
    body += "    " + options.name + "_" + std::to_string(k + 1) + "_run;\n";
  body += home + "  ENDPROC\n";
  program.files.push_back({options.name + ".mod", module(options.name, body, {}, options)});
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const std::string name = options.name + "_" + std::to_string(k + 1);
    // A routine may not share its module's name.
    std::string part_body = "  PROC " + name + "_run()\n";
    std::vector<std::string> part_data;
    for (std::size_t i = parts[k].first; i < parts[k].second; ++i) {
      part_data.push_back(data[i]);
      part_body += moves[i];
    }
    part_body += "  ENDPROC\n";
    program.files.push_back({name + ".mod", module(name, part_body, part_data, options)});
  }
  return program;
}

}  // namespace conform::detail
