#include "conform/pipelines/tube_joint_report.h"

namespace conform {
namespace {

constexpr double kDegPerRad = 57.29577951308232;

ReportGlyphs tool_glyphs(const std::vector<ToolPose>& poses) {
  std::vector<Eigen::Vector3d> at, direction;
  for (const ToolPose& p : poses) at.push_back(p.position), direction.push_back(p.direction);
  return spread_glyphs(at, direction, kTubeJointReportGlyphs);
}

}  // namespace

TubeJointReportFigures tube_joint_report_figures(const TubeJointJobResult& job, double cut_standoff_mm,
                                                 double weld_standoff_mm) {
  TubeJointReportFigures f;
  f.leg_S = job.leg_L;
  for (Eigen::Vector3d& v : f.leg_S.vertices) v = job.T_S_L * v;
  for (Eigen::Vector3d& n : f.leg_S.normals) n = job.T_S_L.linear() * n;
  f.cut_standoff_mm = cut_standoff_mm;
  f.weld_standoff_mm = weld_standoff_mm;
  const TubeJointSolution& s = job.solution;
  if (!s.ok) return f;
  for (const PathFrame& frame : s.frames) f.path.push_back(frame.point);
  if (!f.path.empty()) f.path.push_back(f.path.front());
  f.cut = tool_glyphs(s.tools.cut);
  f.weld = tool_glyphs(s.tools.weld);
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    f.azimuth_deg.push_back(s.frames[i].phi_rad * kDegPerRad);
    f.dihedral_deg.push_back(i < s.tools.psi_rad.size() ? s.tools.psi_rad[i] * kDegPerRad : 0.0);
    f.groove_deg.push_back(i < s.tools.groove_rad.size() ? s.tools.groove_rad[i] * kDegPerRad : 0.0);
    f.weld_deg.push_back(s.tools.weld_angle_rad * kDegPerRad);
  }
  return f;
}

}  // namespace conform
