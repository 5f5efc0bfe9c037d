// Staubli VAL3: the points as pointRx data (.dtx: x, y, z in mm, rx, ry, rz in degrees, R = Rx(rx) Ry(ry) Rz(rz),
// VAL3 reference manual, "trsf") under the work-object frame, and a program (.pgx) that moves through them with movel.

#include <string>

#include "conform/robot/robot_angles.h"
#include "program_writers.h"

namespace conform::detail {

Program write_val3(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  const std::string tool = tool_or(options, "tTool");
  const std::string frame = work_object_or(options, "fPart");
  std::string data =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!-- " + provenance(options, targets.size()) +
      "; rx ry rz in degrees, X-Y'-Z'' -->\n<Database xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
      "xmlns=\"http://www.staubli.com/robotics/VAL3/Data/2\">\n  <Datas>\n";
  data +=
      "    <Data name=\"mPath\" access=\"private\" xsi:type=\"array\" type=\"mdesc\" size=\"1\">\n"
      "      <Value key=\"0\" tvel=\"" +
      num(options.speed_mm_s, 3) +
      (options.blend_mm > 0.0
           ? "\" blend=\"joint\" leave=\"" + num(options.blend_mm, 3) + "\" reach=\"" + num(options.blend_mm, 3) + "\""
           : std::string("\" blend=\"off\"")) +
      " />\n    </Data>\n";
  data +=
      "    <Data name=\"mPathStop\" access=\"private\" xsi:type=\"array\" type=\"mdesc\" size=\"1\">\n"
      "      <Value key=\"0\" tvel=\"" +
      num(options.speed_mm_s, 3) + "\" blend=\"off\" />\n    </Data>\n";
  data +=
      "    <Data name=\"mApproach\" access=\"private\" xsi:type=\"array\" type=\"mdesc\" size=\"1\">\n"
      "      <Value key=\"0\" tvel=\"" +
      num(options.approach_speed_mm_s, 3) + "\" blend=\"off\" />\n    </Data>\n";
  if (!options.home_deg.empty()) {
    data +=
        "    <Data name=\"jHome\" access=\"private\" xsi:type=\"array\" type=\"jointRx\" size=\"1\">\n      <Value "
        "key=\"0\"";
    for (int k = 0; k < 6; ++k) data += " j" + std::to_string(k + 1) + "=\"" + num(options.home_deg[k], 6) + "\"";
    data += " />\n    </Data>\n";
  }
  data += "    <Data name=\"pPath\" access=\"private\" xsi:type=\"array\" type=\"pointRx\" size=\"" +
          std::to_string(targets.size()) + "\">\n";
  std::string code = "begin\n";
  if (!options.home_deg.empty()) code += "  movej(jHome[0], " + tool + ", mApproach)\n";
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RobotTarget& t = targets[i];
    r = euler_xyz_deg(t.rotation, i == 0 ? nullptr : &r);
    data += "      <Value key=\"" + std::to_string(i) + "\" x=\"" + num(t.position_mm.x(), 6) + "\" y=\"" +
            num(t.position_mm.y(), 6) + "\" z=\"" + num(t.position_mm.z(), 6) + "\" rx=\"" + num(r(0), 9) + "\" ry=\"" +
            num(r(1), 9) + "\" rz=\"" + num(r(2), 9) + "\" fatherId=\"" + frame + "[0]\" />\n";
    // mPath blends; a path's first and last points are reached exactly (mPathStop, mApproach do not blend).
    const char* const descriptor = blends(targets, i, options) ? "mPath"
                                   : t.kind == MoveKind::kPath ? "mPathStop"
                                                               : "mApproach";
    // The approach point by a joint move (the robot comes from anywhere), the path and the retract linear.
    code += std::string(t.kind == MoveKind::kApproach ? "  movej(pPath[" : "  movel(pPath[") + std::to_string(i) +
            "], " + tool + ", " + descriptor + ")\n";
    // VAL3 queues its moves: a process line waits for the point to be reached.
    const bool on = starts_path(targets, i) && !options.process_on.empty();
    const bool off = ends_path(targets, i) && !options.process_off.empty();
    if (on || off) code += "  waitEndMove()\n";
    if (on) code += "  " + options.process_on + "\n";
    if (off) code += "  " + options.process_off + "\n";
  }
  data += "    </Data>\n  </Datas>\n</Database>\n";
  if (!options.home_deg.empty()) code += "  movej(jHome[0], " + tool + ", mApproach)\n";
  code += "  waitEndMove()\nend\n";
  const std::string pgx =
      "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<Programs xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
      "xmlns=\"http://www.staubli.com/robotics/VAL3/Program/2\">\n  <Program name=\"" +
      options.name + "\" access=\"public\">\n    <Code><![CDATA[\n" + code + "]]></Code>\n  </Program>\n</Programs>\n";
  Program program;
  program.files.push_back({options.name + ".pgx", pgx});
  program.files.push_back({options.name + ".dtx", data});
  return program;
}

}  // namespace conform::detail
