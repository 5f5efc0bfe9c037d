#pragma once
// The report of `conform tube-joint --report FILE.html` (issue 21): both meshes in the stub frame S, the intersection
// path, and the cutting and welding tools as glyphs from each tool's position to the seam (Eq. 9 and 11, Lind &
// Ystgaard 2020); the dihedral angle, the groove (bevel) angle and the weld angle along the stub azimuth as a plot.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/pipelines/common/report_figures.h"
#include "conform/pipelines/tube_joint/tube_joint.h"
#include "conform/report/page.h"

namespace conform {

// Tool glyphs drawn at most per tool (every k-th path point).
constexpr std::size_t kTubeJointReportGlyphs = 180;

struct TubeJointReportFigures {
  Mesh leg_S;                         // the leg posed into S by T_S_L (empty without keep_geometry)
  std::vector<Eigen::Vector3d> path;  // the seam in S, closed: ends on its first point (empty when !ok)
  ReportGlyphs cut;                   // at the cutting tool's position p_c, direction d_c (Eq. 9)
  ReportGlyphs weld;                  // at the welding torch's position p_w, direction d_w (Eq. 11)
  double cut_standoff_mm = 0.0;       // glyph length: from the tool to the seam
  double weld_standoff_mm = 0.0;
  // Along the path (x: azimuth phi in degrees, from the toe).
  std::vector<double> azimuth_deg, dihedral_deg, groove_deg, weld_deg;
};

// standoffs: the run's (TubeJointJobOptions::solve.tools), the glyphs' lengths.
TubeJointReportFigures tube_joint_report_figures(const TubeJointJobResult& job, double cut_standoff_mm,
                                                 double weld_standoff_mm);

// The page: header (inputs, options, verdict: one closed seam and tools clear, or the failed condition, marked in the
// 3D view where it failed), the meshes (a run with keep_geometry), path and tools, the figures `conform tube-joint`
// prints (cells tied to tube_joint_json), the angles along the azimuth. Page::date is left to the caller.
html::Page tube_joint_report(const TubeJointJobOptions& options, const TubeJointJobResult& job);

}  // namespace conform
