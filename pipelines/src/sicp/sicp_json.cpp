#include "conform/pipelines/sicp/sicp_json.h"

#include "conform/pipelines/common/cad_json.h"

#include <cstddef>

#include "conform/core/error.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {
namespace {

nlohmann::json error_json(const TrajectoryError& e) {
  return {{"path_mean_mm", e.path_mean_mm},
          {"path_max_mm", e.path_max_mm},
          {"mean_mm", e.mean_mm},
          {"rms_mm", e.rms_mm},
          {"max_mm", e.max_mm},
          {"worst_row", e.worst_row},
          {"normal_mean_deg", e.normal_mean_deg},
          {"normal_max_deg", e.normal_max_deg},
          {"max_step_mm", e.max_step_mm},
          {"truth_step_mm", e.truth_step_mm},
          {"normal_step_max_deg", e.normal_step_max_deg},
          {"truth_normal_step_max_deg", e.truth_normal_step_max_deg}};
}

// Each segment of the contour with its fit and its confidence.
nlohmann::json segments_json(const SicpJobResult& r) {
  const SicpCompensationResult& c = r.compensation;
  const SicpResult& g = c.registration;
  nlohmann::json segments = nlohmann::json::array();
  for (std::size_t k = 0; k < g.segments.size(); ++k) {
    const ContourSegment& s = g.segmentation.segments[k];
    const SicpSegmentFit& f = g.segments[k];
    segments.push_back({{"index", k},
                        {"start_mm", s.start_mm},
                        {"length_mm", s.length_mm},
                        {"overlap_before_mm", s.overlap_before_mm},
                        {"overlap_after_mm", s.overlap_after_mm},
                        {"starts_at_corner", s.starts_at_corner},
                        {"ends_at_corner", s.ends_at_corner},
                        {"neighbourhood_points", f.neighbourhood_points},
                        {"stability_points", f.stability_points},
                        {"icp_iterations", f.icp.iterations},
                        {"rms_mm", f.rms_mm},
                        {"off_surface_share", f.off_surface_share},
                        {"converged", f.converged},
                        {"usable", f.usable},
                        {"confidence", k < c.check.segment_confidence.size() ? c.check.segment_confidence[k] : 0.0}});
  }
  return segments;
}

}  // namespace

nlohmann::json sicp_json(const SicpJobResult& r) {
  const SicpCompensationResult& c = r.compensation;
  const SicpResult& g = c.registration;
  nlohmann::json j = {{"model", to_string(c.model)},
                      {"converged", c.converged},
                      {"termination", c.termination},
                      {"rms_mm", c.model == SicpModel::kSicp ? g.rms_mm : g.coarse.rms_mm},
                      {"segments", segments_json(r)},
                      {"corners", g.segmentation.corners.size()},
                      {"contour_source", r.contour_source},
                      {"contour_points", r.contour_points},
                      {"contour_length_mm", r.contour_length_mm},
                      {"scan_points", r.scan_points},
                      {"scan_points_used", g.scan_points_used},
                      {"scan_edge_points", g.scan_edge.size()},
                      {"surface_faces", r.surface_faces},
                      {"trajectory_rows", r.trajectory_rows},
                      {"normals_from_scan", c.normals_from_scan},
                      {"rigid",
                       {{"T_scan_nominal", json_of(g.T_scan_nominal_rigid)},
                        {"rms_mm", g.coarse.rms_mm},
                        {"iterations", g.coarse.iterations},
                        {"converged", g.coarse.converged}}},
                      {"joint",
                       {{"ran", g.joint.ran},
                        {"usable", g.joint.usable},
                        {"termination", g.joint.termination},
                        {"solver_iterations", g.joint.solver_iterations},
                        {"max_disagreement_before_mm", g.joint.max_disagreement_before_mm},
                        {"max_disagreement_after_mm", g.joint.max_disagreement_after_mm}}},
                      {"checks",
                       {{"trusted", c.trusted},
                        {"reason", c.check.reason},
                        {"noise_mm", c.check.noise_mm},
                        {"blind_segments", c.check.blind_segments},
                        {"outlier_segments", c.check.outlier_segments},
                        {"off_surface_segments", c.check.off_surface_segments},
                        {"untrusted_rows", c.check.untrusted_rows},
                        {"far_rows", c.check.far_rows},
                        {"unmeasured_rows", c.check.unmeasured_rows},
                        {"bridged_rows", c.check.bridged_rows},
                        {"longest_gap_mm", c.check.longest_gap_mm},
                        {"off_edge_rows", c.check.off_edge_rows},
                        {"max_edge_offset_mm", c.check.max_edge_offset_mm},
                        {"jump_rows", c.check.jump_rows},
                        {"max_row_step_mm", c.check.max_row_step_mm},
                        {"misfit_rows", c.check.misfit_rows},
                        {"unanchored_rows", c.check.unanchored_rows},
                        {"max_surface_offset_mm", c.check.max_surface_offset_mm},
                        {"max_normal_error_deg", c.check.max_normal_error_deg},
                        {"max_local_offset_mm", c.check.max_local_offset_mm},
                        {"max_dent_slope_deg", c.check.max_dent_slope_deg},
                        {"min_confidence", c.check.min_confidence}}},
                      {"trusted", c.trusted},
                      {"out_trajectory", r.out_trajectory_path},
                      {"out_rows", r.out_rows_path},
                      {"warnings", r.warnings}};
  if (c.model == SicpModel::kProjection) {
    const ProjectionModel& p = c.projection;
    j["projection"] = {
        {"fit", to_string(p.fit)}, {"samples", p.samples}, {"rms_mm", p.rms_mm}, {"normal", json_of(p.normal)}};
  }
  if (r.error) j["error"] = error_json(*r.error);
  j["cad"] = cad_json(r.cad_inputs);
  return j;
}

void set_sicp_choices(const std::string& model, const std::string& fit, const std::string& normals,
                      SicpCompensationOptions* options) {
  if (model == "sicp") {
    options->model = SicpModel::kSicp;
  } else if (model == "rigid") {
    options->model = SicpModel::kRigid;
  } else if (model == "projection") {
    options->model = SicpModel::kProjection;
  } else {
    throw Error("--model " + model + ": use sicp, rigid or projection");
  }
  if (fit == "parabola") {
    options->projection.fit = ProjectionFit::kParabola;
  } else if (fit == "spline") {
    options->projection.fit = ProjectionFit::kThinPlateSpline;
  } else {
    throw Error("--projection-fit " + fit + ": use parabola or spline");
  }
  if (normals != "scan" && normals != "rotate") throw Error("--normals " + normals + ": use rotate or scan");
  options->normals.from_scan = normals == "scan";
}

}  // namespace conform
