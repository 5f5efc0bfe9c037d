#pragma once
// Reduced generated panels for the S-ICP tests (fast, also under sanitizers): the full-size figures come from
// bench/sicp_bench.cpp and docs/sicp.md. Each scenario runs the three models on the same data; the new panels of
// issue 30 (new_panel) run one model and are judged by the bar or a refusal (meets_bar_or_refused).

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/compensation/trajectory_error.h"
#include "conform/datasets/panel.h"
#include "conform/pipelines/sicp/sicp.h"

namespace conform::test {

struct ModelErrors {
  SicpCompensationResult sicp, rigid, projection;
  TrajectoryError sicp_error, rigid_error, projection_error;
};

inline PanelOptions reduced(PanelShape shape) {
  PanelOptions o;
  o.shape = shape;
  o.scan_points = shape == PanelShape::kPlate ? 30000 : 50000;
  o.contour_spacing_mm = 1.0;
  o.surface_edge_mm = 3.0;
  o.seed = 11;
  return o;
}

// with_projection: also run the projection model (the robustness tests skip it, to stay fast under sanitizers).
inline ModelErrors run_models(const PanelOptions& options, bool with_projection = true) {
  const PanelData panel = generate_panel(options);
  std::vector<Eigen::Vector3d> scan;
  for (const pcl::PointXYZ& p : panel.scan.points) scan.emplace_back(p.x, p.y, p.z);
  const Trajectory nominal{panel.trajectory.points, panel.trajectory.normals};
  const Trajectory truth{panel.truth.points, panel.truth.normals};
  ModelErrors m;
  SicpCompensationOptions o;
  o.model = SicpModel::kSicp;
  m.sicp = compensate_trajectory(panel.contour, &panel.surface, scan, nominal, o);
  o.model = SicpModel::kRigid;
  m.rigid = compensate_trajectory(panel.contour, &panel.surface, scan, nominal, o);
  if (with_projection) {
    o.model = SicpModel::kProjection;
    m.projection = compensate_trajectory(panel.contour, &panel.surface, scan, nominal, o);
    m.projection_error = trajectory_error(m.projection.trajectory, truth, nominal);
  }
  m.sicp_error = trajectory_error(m.sicp.trajectory, truth, nominal);
  m.rigid_error = trajectory_error(m.rigid.trajectory, truth, nominal);
  return m;
}

// The bar: S-ICP cuts the mean error by >= 75% and the peak error by >= 60% relative to rigid ICP (the paper
// reports 57% and 45%), measured off the true path; the correction changes by less than the noise from one row to
// the next (no jump at a junction). Rows: 1 mm apart.
inline void expect_sicp_beats_rigid(const ModelErrors& m, double noise_mm, double peak_ratio = 0.40) {
  EXPECT_TRUE(m.sicp.converged) << m.sicp.termination;
  EXPECT_TRUE(m.rigid.converged);
  EXPECT_LE(m.sicp_error.path_mean_mm, 0.25 * m.rigid_error.path_mean_mm)
      << "S-ICP " << m.sicp_error.path_mean_mm << " mm, rigid " << m.rigid_error.path_mean_mm << " mm";
  EXPECT_LE(m.sicp_error.path_max_mm, peak_ratio * m.rigid_error.path_max_mm)
      << "S-ICP " << m.sicp_error.path_max_mm << " mm, rigid " << m.rigid_error.path_max_mm << " mm";
  EXPECT_LT(m.sicp_error.max_step_mm, noise_mm);
  EXPECT_EQ(m.sicp.trajectory.points.size(), m.rigid.trajectory.points.size());
}

// The panel, reduced: a 240 x 160 mm porthole (or cut-out with 6 mm corners) in the curved plate, a smooth
// field of 7.5 mm, a 50 mm band, moved rigidly by about 1 deg and 3 mm.
inline PanelOptions new_panel(PlateOpening opening, std::uint64_t seed) {
  PanelOptions o = harder_plate(opening, seed);
  o.porthole_width_mm = 240.0;
  o.porthole_height_mm = 160.0;
  o.field_mm = 7.5;
  o.band_mm = 50.0;
  o.rotation_deg = Eigen::Vector3d(0.6, -0.5, 0.6);
  o.translation_mm = Eigen::Vector3d(2.0, -1.5, 1.6);
  o.scan_points = 30000;
  o.contour_spacing_mm = 1.0;
  o.surface_edge_mm = 3.0;
  return o;
}

struct PanelRun {
  SicpCompensationResult result;
  TrajectoryError error;
};

inline PanelRun run(const PanelOptions& options, SicpModel model = SicpModel::kSicp) {
  const PanelData panel = generate_panel(options);
  std::vector<Eigen::Vector3d> scan;
  for (const pcl::PointXYZ& p : panel.scan.points) scan.emplace_back(p.x, p.y, p.z);
  const Trajectory nominal{panel.trajectory.points, panel.trajectory.normals};
  const Trajectory truth{panel.truth.points, panel.truth.normals};
  SicpCompensationOptions o;
  o.model = model;
  PanelRun r;
  r.result = compensate_trajectory(panel.contour, &panel.surface, scan, nominal, o);
  r.error = trajectory_error(r.result.trajectory, truth, nominal);
  return r;
}

// Off the bar: peak off path above 0.6 mm, mean above 0.2 mm, tool normals beyond 3 deg or a jump above 0.2 mm.
inline bool beyond_bar(const TrajectoryError& e) {
  return e.path_mean_mm > 0.2 || e.path_max_mm > 0.6 || e.normal_max_deg > 3.0 || e.max_step_mm > 0.2;
}

// The bar, or refused with a reason; prints the figures. Returns whether the path was trusted.
inline bool meets_bar_or_refused(const PanelRun& r, const std::string& what) {
  const TrajectoryError& e = r.error;
  std::printf("%-44s %-8s off path %.3f / %.3f mm, normals %.2f / %.2f deg, step %.3f mm%s%s\n", what.c_str(),
              r.result.trusted ? "trusted" : "refused", e.path_mean_mm, e.path_max_mm, e.normal_mean_deg,
              e.normal_max_deg, e.max_step_mm, r.result.trusted ? "" : ": ", r.result.check.reason.c_str());
  if (std::getenv("SICP_MATRIX_VERBOSE") != nullptr) {
    const SicpCheck& c = r.result.check;
    std::printf("  edge points %zu, noise %.4f, surface misfit %.3f mm, %.2f deg, local %.3f mm (%zu rows)\n",
                r.result.registration.scan_edge.size(), c.noise_mm, c.max_surface_offset_mm, c.max_normal_error_deg,
                c.max_local_offset_mm, c.misfit_rows);
    std::printf("  dent slope %.2f deg (significant, largest)\n", c.max_dent_slope_deg);
    for (const std::string& w : r.result.registration.warnings) std::printf("  %s\n", w.c_str());
    for (const std::string& w : r.result.check.warnings) std::printf("  %s\n", w.c_str());
    for (const SicpSegmentFit& f : r.result.registration.segments)
      std::printf("  [%zu %zu %.3f]", f.neighbourhood_points, f.stability_points, f.rms_mm);
    std::printf("\n");
  }
  if (!r.result.trusted) {
    EXPECT_FALSE(r.result.check.reason.empty()) << what;
    return false;
  }
  EXPECT_LE(e.path_mean_mm, 0.2) << what;
  EXPECT_LE(e.path_max_mm, 0.6) << what;
  EXPECT_LE(e.normal_max_deg, 3.0) << what;
  EXPECT_LE(e.max_step_mm, 0.2) << what;
  return true;
}

}  // namespace conform::test
