// The frames as CSV: i,segment,kind,x_mm,y_mm,z_mm,qw,qx,qy,qz,a_deg,b_deg,c_deg (quaternion scalar first; A B C the
// Z-Y'-X'' angles of krl); for checking, plotting or a controller this project does not write.

#include <string>

#include "conform/core/csv.h"
#include "conform/robot/robot_angles.h"
#include "program_writers.h"

namespace conform::detail {

Program write_frames_csv(const std::vector<RobotTarget>& targets, const ProgramOptions& options) {
  CsvWriter csv({"i", "segment", "kind", "x_mm", "y_mm", "z_mm", "qw", "qx", "qy", "qz", "a_deg", "b_deg", "c_deg"},
                12);
  Eigen::Vector4d q = Eigen::Vector4d::Zero();
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const RobotTarget& t = targets[i];
    q = quaternion_wxyz(t.rotation, i == 0 ? nullptr : &q);
    abc = euler_zyx_deg(t.rotation, i == 0 ? nullptr : &abc);
    const char* kind = t.kind == MoveKind::kPath ? "path" : (t.kind == MoveKind::kApproach ? "approach" : "retract");
    csv.cell(static_cast<std::int64_t>(i)).cell(static_cast<std::int64_t>(t.segment)).cell(std::string_view(kind));
    for (int k = 0; k < 3; ++k) csv.cell(t.position_mm(k));
    for (int k = 0; k < 4; ++k) csv.cell(q(k));
    for (int k = 0; k < 3; ++k) csv.cell(abc(k));
    csv.end_row();
  }
  Program program;
  program.files.push_back({options.name + ".csv", csv.text()});
  return program;
}

}  // namespace conform::detail
