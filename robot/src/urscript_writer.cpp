// Universal Robots URScript (.script): movel(p[x, y, z, rx, ry, rz], a, v[, r]) with positions in metres and the
// rotation vector (axis times angle, rad) of the tool frame in the base frame (URScript manual, "pose"); r, the blend
// radius in metres, on the interior points of a path (without it the robot stops at every point).

#include <string>

#include "conform/core/constants.h"
#include "conform/robot/robot_angles.h"
#include "program_writers.h"

namespace conform::detail {

Program write_urscript(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  std::string text = "def " + options.name + "():\n  # " + provenance(options, targets.size()) +
                     "\n  # poses p[x, y, z, rx, ry, rz]: metres and a rotation vector in radians\n";
  if (!options.tool.empty()) text += "  # tool: " + options.tool + " (set the TCP in the installation)\n";
  if (!options.work_object.empty()) text += "  # work object: " + options.work_object + "\n";
  std::string home;
  if (!options.home_deg.empty()) {
    home = "  movej([" + num(options.home_deg[0] * kPi / 180.0, 9);
    for (int k = 1; k < 6; ++k) home += ", " + num(options.home_deg[k] * kPi / 180.0, 9);
    home += "])  # home, rad\n";
  }
  text += home;
  Eigen::Vector3d rv = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RobotTarget& t = targets[i];
    rv = rotation_vector(t.rotation, i == 0 ? nullptr : &rv);
    const double v = (t.kind == MoveKind::kPath ? options.speed_mm_s : options.approach_speed_mm_s) / 1000.0;
    const Eigen::Vector3d p = t.position_mm / 1000.0;
    // The approach point by a joint move (movej with a pose: the controller solves the joints; its default joint
    // speed and acceleration), the path and the retract linear.
    const bool joint = t.kind == MoveKind::kApproach;
    text += std::string(joint ? "  movej(p[" : "  movel(p[") + num(p.x(), 9) + ", " + num(p.y(), 9) + ", " +
            num(p.z(), 9) + ", " + num(rv.x(), 12) + ", " + num(rv.y(), 12) + ", " + num(rv.z(), 12) +
            (joint ? std::string("]") : "], a=0.5, v=" + num(v, 6)) +
            (blends(targets, i, options) ? ", r=" + num(options.blend_mm / 1000.0, 6) : std::string()) + ")\n";
    if (starts_path(targets, i) && !options.process_on.empty()) text += "  " + options.process_on + "\n";
    if (ends_path(targets, i) && !options.process_off.empty()) text += "  " + options.process_off + "\n";
  }
  text += home + "end\n";
  Program program;
  program.files.push_back({options.name + ".script", text});
  return program;
}

}  // namespace conform::detail
