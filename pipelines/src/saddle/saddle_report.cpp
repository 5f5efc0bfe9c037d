#include "conform/pipelines/saddle/saddle_report.h"

#include <algorithm>
#include <cmath>

#include "conform/core/constants.h"
#include "conform/toolpath/saddle/saddle_curve.h"

#include "common/report_pages.h"

namespace conform {
namespace {


constexpr int kAround = 96;  // context meshes: azimuth steps of the pipe, grid steps of the leg patch

// Quads between two rows of `cols` vertices each, row-major from vertex `first`.
void add_quads(Mesh* m, int rows, int cols, bool wrap) {
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c < (wrap ? cols : cols - 1); ++c) {
      const int a = r * cols + c, b = r * cols + (c + 1) % cols, d = a + cols, e = b + cols;
      m->faces.push_back({a, b, e});
      m->faces.push_back({a, e, d});
    }
  }
}

// The pipe's wall between the seam and r above the seam's highest point.
Mesh pipe_mesh(const SaddleCurve& curve) {
  const double r = curve.geometry().pipe_radius_mm;
  Mesh m;
  double top = -1e300;
  for (int k = 0; k < kAround; ++k) top = std::max(top, curve.point(2.0 * kPi * k / kAround).z());
  for (const bool upper : {false, true}) {
    for (int k = 0; k < kAround; ++k) {
      const double phi = 2.0 * kPi * k / kAround;
      const Eigen::Vector3d seam = curve.point(phi);
      m.vertices.emplace_back(seam.x(), seam.y(), upper ? top + r : seam.z());
    }
  }
  add_quads(&m, 2, kAround, true);
  return m;
}

// The cylinder's patch under the seam: the seam's extent in the leg frame L (azimuth about z_L, height along it) and
// r / 2 around it, carried into P.
Mesh leg_mesh(const SaddleCurve& curve) {
  const SaddleGeometry& g = curve.geometry();
  const Eigen::Isometry3d T_L = T_L_P(g.joint());
  double a_lo = 1e300, a_hi = -1e300, z_lo = 1e300, z_hi = -1e300;
  for (int k = 0; k < kAround; ++k) {
    const Eigen::Vector3d p = T_L * curve.point(2.0 * kPi * k / kAround);
    a_lo = std::min(a_lo, std::atan2(p.y(), p.x())), a_hi = std::max(a_hi, std::atan2(p.y(), p.x()));
    z_lo = std::min(z_lo, p.z()), z_hi = std::max(z_hi, p.z());
  }
  const double margin = 0.5 * g.pipe_radius_mm;
  a_lo -= margin / g.leg_radius_mm, a_hi += margin / g.leg_radius_mm, z_lo -= margin, z_hi += margin;
  const int n = kAround / 4;
  Mesh m;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double a = a_lo + (a_hi - a_lo) * i / (n - 1), z = z_lo + (z_hi - z_lo) * j / (n - 1);
      const Eigen::Vector3d p_L(g.leg_radius_mm * std::cos(a), g.leg_radius_mm * std::sin(a), z);
      m.vertices.push_back(T_L.inverse() * p_L);
    }
  }
  add_quads(&m, n, n, false);
  return m;
}

using html::count;
using html::number;

html::Table figures_table(const SaddleJobResult& job, const SaddleReportFigures& f) {
  const SaddleResult& s = job.saddle;
  html::Table t{"Interpolation", {"figure", "value"}, {}};
  t.rows.push_back({"interpolation", {to_string(s.rule), "/interpolation"}});
  t.rows.push_back({"points", count(s.points.size(), "/points")});
  t.rows.push_back({"step min (mm)", number(s.step_mm_min, 6, "/step_mm_min")});
  t.rows.push_back({"step mean (mm)", number(s.step_mm_mean, 6, "/step_mm_mean")});
  t.rows.push_back({"step max (mm)", number(s.step_mm_max, 6, "/step_mm_max")});
  t.rows.push_back({"last step (mm)", number(s.last_step_mm, 6, "/last_step_mm")});
  t.rows.push_back({"speed ripple (%)", number(s.speed_ripple_pct, 6, "/speed_ripple_pct")});
  t.rows.push_back({"path length (mm)", number(s.path_length_mm, 6, "/path_length_mm")});
  t.rows.push_back({"seam length (mm)", number(s.curve_length_mm, 6, "/curve_length_mm")});
  t.rows.push_back({"pose min (deg)", number(s.pose_rad_min * kDegPerRad, 4, "/pose_deg_min")});
  t.rows.push_back({"pose max (deg)", number(s.pose_rad_max * kDegPerRad, 4, "/pose_deg_max")});
  t.rows.push_back({"off the pipe, max (mm)", html::number_g(s.max_pipe_residual_mm, 3, "/max_pipe_residual_mm")});
  t.rows.push_back(
      {"off the cylinder, max (mm)", html::number_g(s.max_leg_residual_mm, 3, "/max_cylinder_residual_mm")});
  t.rows.push_back({"path vs closed form, max (mm)", html::number_g(f.max_position_error_mm, 3)});
  t.rows.push_back({"pose vs closed form, max (deg)", html::number_g(f.max_pose_error_deg, 3)});
  return t;
}

std::vector<html::Plot> plots(const SaddleReportFigures& f) {
  html::Plot z = detail::line_plot("Height of the seam along the pipe axis: path and closed form (Eq. 7)",
                                   "theta (deg)", "z (mm)");
  z.series = {detail::series("closed form", f.theta_deg, f.closed_z_mm, html::kGrey),
              detail::series("path", f.theta_deg, f.z_mm, html::kBlue, f.theta_deg.size() <= 400)};
  html::Plot pose = detail::line_plot("Torch pose angle: path and closed form (Eq. 12)", "theta (deg)", "pose (deg)");
  pose.series = {detail::series("closed form", f.theta_deg, f.closed_pose_deg, html::kGrey),
                 detail::series("path", f.theta_deg, f.pose_deg, html::kOrange, f.theta_deg.size() <= 400)};
  html::Plot step = detail::line_plot("Step length", "theta (deg)", "3D step from the previous point (mm)");
  // The first point has no step: start the line at the second.
  const std::vector<double> x(f.theta_deg.begin() + (f.theta_deg.empty() ? 0 : 1), f.theta_deg.end());
  const std::vector<double> y(f.step_mm.begin() + (f.step_mm.empty() ? 0 : 1), f.step_mm.end());
  step.series = {detail::series("step", x, y, html::kGreen)};
  return {z, pose, step};
}

}  // namespace

Eigen::Vector3d saddle_torch_direction(double theta_rad, double pose_rad) {
  const Eigen::Vector3d n_p(std::sin(theta_rad), std::cos(theta_rad), 0.0);
  return std::cos(pose_rad) * Eigen::Vector3d::UnitZ() + std::sin(pose_rad) * n_p;
}

SaddleReportFigures saddle_report_figures(const SaddleJobOptions& options, const SaddleJobResult& job) {
  SaddleReportFigures f;
  const std::vector<SaddlePoint>& points = job.saddle.points;
  if (points.empty()) return f;
  const SaddleCurve curve(options.saddle.geometry);
  f.pipe = pipe_mesh(curve);
  f.leg = leg_mesh(curve);
  for (const SaddlePoint& p : points) {
    f.max_position_error_mm = std::max(f.max_position_error_mm, (p.position - curve.point(p.theta_rad)).norm());
    const double pose = curve.pose(p.theta_rad, options.saddle.start_pose_rad);
    f.max_pose_error_deg = std::max(f.max_pose_error_deg, std::abs(p.pose_rad - pose) * kDegPerRad);
  }
  for (const std::size_t i : spread_indices(points.size(), kSaddleReportPoints)) {
    const SaddlePoint& p = points[i];
    f.path.push_back(p.position);
    f.theta_deg.push_back(p.theta_rad * kDegPerRad);
    f.z_mm.push_back(p.position.z());
    f.closed_z_mm.push_back(curve.point(p.theta_rad).z());
    f.pose_deg.push_back(p.pose_rad * kDegPerRad);
    f.closed_pose_deg.push_back(curve.pose(p.theta_rad, options.saddle.start_pose_rad) * kDegPerRad);
    f.step_mm.push_back(p.step_mm);
  }
  // The last point is the first again (theta 2 pi): one glyph there is enough.
  for (const std::size_t i : spread_indices(points.size() - 1, kSaddleReportGlyphs)) {
    f.torch.origins.push_back(points[i].position);
    f.torch.directions.push_back(saddle_torch_direction(points[i].theta_rad, points[i].pose_rad));
  }
  return f;
}

html::Page saddle_report(const SaddleRequest& request, const SaddleJobOptions& options, const SaddleJobResult& job) {
  html::Page page;
  page.job = "saddle";
  const nlohmann::json j = saddle_json(request, job);
  page.options = {{"R_mm", request.leg_radius_mm},
                  {"r_mm", request.pipe_radius_mm},
                  {"pitch_deg", request.pitch_deg},
                  {"offset_mm", request.offset_mm},
                  {"right_angle_pose_deg", request.right_angle_pose_deg},
                  {"step_deg", j["step_deg"]},
                  {"speed_mm_per_s", j["speed_mm_per_s"]},
                  {"period_s", j["period_s"]}};
  const SaddleResult& s = job.saddle;
  page.verdict = s.converged ? html::Verdict{html::Level::kOk, "converged: " + std::to_string(s.points.size()) +
                                                                   " points, " + to_string(s.rule)}
                             : html::Verdict{html::Level::kFail, s.termination + "; no file written"};
  page.result = j;
  const SaddleReportFigures f = saddle_report_figures(options, job);
  page.scene.add_mesh("pipe", f.pipe, html::kBlue, 0.3);
  page.scene.add_mesh("cylinder (leg)", f.leg, html::kGrey, 0.45);
  page.scene.add_polyline("seam path", f.path, html::kRed);
  // Torch glyphs a quarter of the pipe radius long.
  page.scene.add_arrows("torch", f.torch.origins, f.torch.directions, request.pipe_radius_mm / 4.0, html::kOrange);
  page.sections.push_back(
      {"Figures",
       {"Paper frame P (Xue et al. 2018, Fig. 2): z along the pipe axis away from the cylinder, y "
        "towards the toe. Torch glyphs: from the seam towards the torch, at the pose angle from the "
        "pipe axis in the plane of the axis and the pipe's normal."},
       {figures_table(job, f)},
       plots(f)});
  return page;
}

}  // namespace conform
