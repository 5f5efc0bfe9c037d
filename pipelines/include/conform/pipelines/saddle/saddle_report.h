#pragma once
// The report of `conform saddle --report FILE.html` (issue 21): the interpolated seam in the paper frame P with the
// torch as glyphs, and along the machine's rotation angle theta the path against its closed form (saddle_curve.h):
// the height z(theta) and the pose angle (Eq. 7 and 12, Xue et al. 2018), and the step lengths.
//
// The torch direction (from the seam towards the torch) is cos(pose) z_P + sin(pose) n_p(theta), n_p = (sin theta,
// cos theta, 0): the tool axis that `conform export` gives a saddle path (robot/job_paths.h), reversed.

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/pipelines/common/report_figures.h"
#include "conform/pipelines/saddle/saddle.h"
#include "conform/pipelines/saddle/saddle_json.h"
#include "conform/report/page.h"

namespace conform {

// At most this many path points drawn and plotted (the paper's 80 mm/min path has 177,427), and torch glyphs.
constexpr std::size_t kSaddleReportPoints = 4000;
constexpr std::size_t kSaddleReportGlyphs = 120;

struct SaddleReportFigures {
  std::vector<Eigen::Vector3d> path;  // the interpolation points in P, decimated to kSaddleReportPoints
  ReportGlyphs torch;                 // at the seam, towards the torch, at most kSaddleReportGlyphs
  // Per plotted point (the same decimation as path): theta in degrees, the path's z and pose, the closed form's.
  std::vector<double> theta_deg, z_mm, closed_z_mm, pose_deg, closed_pose_deg, step_mm;
  // Context, in P: the pipe's wall from the seam up to r above its highest point, and the patch of the cylinder
  // (leg) under the seam with r / 2 around it.
  Mesh pipe;
  Mesh leg;
  // Over every point (not only the plotted ones): the largest |path - closed form|.
  double max_position_error_mm = 0.0;
  double max_pose_error_deg = 0.0;
};

// The torch direction at a seam point (above).
Eigen::Vector3d saddle_torch_direction(double theta_rad, double pose_rad);

SaddleReportFigures saddle_report_figures(const SaddleJobOptions& options, const SaddleJobResult& job);

// The page: header (the request as options, verdict: converged or why not), the seam and the torch in 3D, the
// figures `conform saddle` prints (cells tied to saddle_json), the path against its closed form along theta.
// Page::date is left to the caller.
html::Page saddle_report(const SaddleRequest& request, const SaddleJobOptions& options, const SaddleJobResult& job);

}  // namespace conform
