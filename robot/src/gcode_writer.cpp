// ISO G-code (.nc), Siemens SINUMERIK 840D dialect: 3-axis G1 X Y Z, or 5-axis with TRAORI and the tool orientation
// as a vector A3= B3= C3= (the direction from the tool tip to the tool holder, i.e. -z of the tool frame: (0, 0, 1)
// for a vertical tool; Siemens programming manual, "Orientation programming"); F in mm/min, G94.

#include <string>

#include "program_writers.h"

namespace conform::detail {

Program write_gcode(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  std::string text = "; " + provenance(options, targets.size()) + "\n; Siemens 840D: " +
                     (options.five_axis ? "5-axis TRAORI, A3 B3 C3 = tool vector (tip -> holder)" : "3-axis") +
                     ", mm, mm/min\n";
  if (!options.tool.empty()) text += "T=\"" + options.tool + "\" M6\n";
  if (!options.work_object.empty()) text += options.work_object + "\n";
  text += "G17 G90 G94 G71\n";
  if (options.five_axis) text += "TRAORI\nORIWKS\n";
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RobotTarget& t = targets[i];
    const double feed = (t.kind == MoveKind::kPath ? options.speed_mm_s : options.approach_speed_mm_s) * 60.0;
    // The approach point at rapid traverse (G0), the path and the retract at the feed (G1).
    text += std::string(t.kind == MoveKind::kApproach ? "G0" : "G1") + " X" + num(t.position_mm.x(), 6) + " Y" +
            num(t.position_mm.y(), 6) + " Z" + num(t.position_mm.z(), 6);
    if (options.five_axis) {
      const Eigen::Vector3d v = -t.rotation.col(2);
      text += " A3=" + num(v.x(), 12) + " B3=" + num(v.y(), 12) + " C3=" + num(v.z(), 12);
    }
    text += t.kind == MoveKind::kApproach ? std::string("\n") : " F" + num(feed, 3) + "\n";
    if (starts_path(targets, i) && !options.process_on.empty()) text += options.process_on + "\n";
    if (ends_path(targets, i) && !options.process_off.empty()) text += options.process_off + "\n";
  }
  if (options.five_axis) text += "TRAFOOF\n";
  text += "M30\n";
  Program program;
  program.files.push_back({options.name + ".nc", text});
  return program;
}

}  // namespace conform::detail
