#include "conform/pipelines/tube_joint/tube_joint_json.h"

#include "conform/core/constants.h"
#include "conform/pipelines/common/cad_json.h"

#include <utility>

#include "conform/core/csv.h"
#include "conform/core/error.h"

namespace conform {
namespace {


// CSV `phi_deg,alpha_deg`: the groove table of Eq. (5), generalised.
std::vector<std::pair<double, double>> read_groove_table(const std::string& path) {
  const CsvTable table = read_csv(path, {"phi_deg", "alpha_deg"});
  const Eigen::MatrixXd rows = table.numbers({"phi_deg", "alpha_deg"});
  if (rows.rows() == 0) throw Error(path + ": the groove table has no rows");
  std::vector<std::pair<double, double>> out;
  for (Eigen::Index i = 0; i < rows.rows(); ++i) out.emplace_back(radians(rows(i, 0)), radians(rows(i, 1)));
  GrooveTable check(out, GrooveInterpolation::kLinear);
  std::string why;
  if (!check.IsValid(&why)) throw Error(path + ": " + why);
  return out;
}

nlohmann::json violation(const ToolViolation& v) {
  return {{"count", v.count}, {"first_azimuth_deg", v.count > 0 ? degrees(v.first_phi_rad) : 0.0}};
}

nlohmann::json reference(const TubeReferenceResult& r) {
  return {{"method", r.method},
          {"residuals_mm", r.marker_residuals_mm},
          {"rms_mm", r.marker_rms_mm},
          {"max_mm", r.marker_max_mm},
          {"fit_axis_disagreement_deg", r.axis_disagreement_deg},
          {"fit_axis_offset_mm", r.axis_offset_mm}};
}

void add_robustness(const TubeJointJobResult& r, nlohmann::json* j) {
  const TubeJointSolution& s = r.solution;
  (*j)["warnings"] = s.warnings;
  (*j)["leg_welded_vertices"] = s.leg_welded_vertices;
  (*j)["stub_welded_vertices"] = s.stub_welded_vertices;
  (*j)["leg_weld_tolerance_mm"] = s.leg_weld_tolerance_mm;
  (*j)["normal_sigma_deg_max"] = s.normal_sigma_deg_max;
  (*j)["tangent_sigma_deg_max"] = s.tangent_sigma_deg_max;
  (*j)["stub_weld_tolerance_mm"] = s.stub_weld_tolerance_mm;
  (*j)["islands"] = s.islands;
  (*j)["longest_island_mm"] = s.longest_island_mm;
  (*j)["merged_vertices"] = s.merged_vertices;
  (*j)["backtrack_tolerance_mm"] = s.backtrack_tolerance_mm;
  (*j)["max_backtrack_mm"] = s.max_backtrack_mm;
  for (const auto& [name, q] : {std::pair<const char*, const ScanQuality*>{"leg", &s.leg_quality},
                                std::pair<const char*, const ScanQuality*>{"stub", &s.stub_quality}}) {
    (*j)[std::string(name) + "_scan"] = {
        {"noise_mm", q->noise_mm},
        {"edge_mm", q->edge_mm},
        {"curvature_radius_mm", q->curvature_per_mm > 0 ? 1.0 / q->curvature_per_mm : 0.0},
        {"edge_angle_deg", q->edge_angle_deg}};
  }
  (*j)["refined_points"] = s.refined_points;
  (*j)["min_crossing_deg"] = s.min_crossing_deg;
  (*j)["facet_error_mm"] = s.facet_error_mm;
  (*j)["leg_radius_mm"] = r.leg_radius_mm;
  (*j)["stub_radius_mm"] = r.stub_radius_mm;
  const ToolSafetyResult& safety = s.safety;
  (*j)["safety"] = {{"ok", safety.ok},
                    {"walls_checked", safety.walls_checked},
                    {"groove_beyond_wall", violation(safety.groove_beyond_wall)},
                    {"cut_tip_in_stub", violation(safety.cut_tip_in_stub)},
                    {"cut_line_in_stub", violation(safety.cut_line_in_stub)},
                    {"weld_tip_in_stub", violation(safety.weld_tip_in_stub)},
                    {"weld_tip_in_leg", violation(safety.weld_tip_in_leg)},
                    {"weld_line_in_material", violation(safety.weld_line_in_material)}};
  if (!r.leg_marker_residuals_mm.empty()) (*j)["leg_markers"] = reference(r.leg_reference);
  if (!r.stub_marker_residuals_mm.empty()) (*j)["stub_markers"] = reference(r.stub_reference);
}

}  // namespace

TubeJointJobOptions tube_joint_job_options(const TubeJointRequest& request) {
  TubeJointJobOptions o = request.job;
  if (o.leg_pose_path.empty() && !request.pitch_deg) {
    throw Error("tube-joint: give the joint as --pitch-deg A --offset MM --protrusion MM, or --leg-pose FILE");
  }
  if (o.leg_pose_path.empty() && !request.protrusion_given) {
    throw Error("tube-joint: give --protrusion MM (the stub's distal end to the leg axis, along the stub axis)");
  }
  o.spec.pitch_rad = radians(request.pitch_deg.value_or(90.0));
  if (request.step_mm) {
    o.solve.sampling.spacing = PathSpacing::kArcLength;
    o.solve.sampling.step_mm = *request.step_mm;
  } else {
    o.solve.sampling.step_rad = radians(request.step_deg);
  }
  o.solve.sampling.smoothing_mm2 = request.smoothing_mm2;
  o.solve.sampling.smoothing_rms_mm = request.smoothing_rms_mm;
  if (request.groove_deg) {
    const std::array<double, 4>& g = *request.groove_deg;
    o.solve.tools.groove_rad = {radians(g[0]), radians(g[1]), radians(g[2]), radians(g[3])};
  }
  if (!request.groove_table_path.empty()) o.solve.tools.groove_table_rad = read_groove_table(request.groove_table_path);
  const std::string& i = request.interpolation;
  if (i != "linear" && i != "quadratic" && i != "spline") {
    throw Error("--groove-interpolation " + i + ": use linear, quadratic or spline");
  }
  o.solve.tools.interpolation = i == "quadratic" ? GrooveInterpolation::kQuadratic
                                : i == "spline"  ? GrooveInterpolation::kSpline
                                                 : GrooveInterpolation::kLinear;
  const std::vector<double>& w = request.walls_mm;
  if (w.size() > 2) throw Error("--wall-thickness: give MM or LEG_MM,STUB_MM");
  for (const double d : w) {
    if (!(d > 0.0)) throw Error("--wall-thickness: wall thicknesses must be > 0 mm");
  }
  if (!w.empty()) {
    o.solve.safety.leg_wall_mm = w[0];
    o.solve.safety.stub_wall_mm = w.back();
  }
  o.solve.tools.weld_angle_rad = radians(request.weld_angle_deg);
  return o;
}

nlohmann::json tube_joint_json(const TubeJointJobResult& r) {
  const TubeJointSolution& s = r.solution;
  const bool ok = s.ok;
  nlohmann::json j = {{"ok", ok},
                      {"closed", ok},
                      {"termination", s.termination},
                      {"condition", ok ? nlohmann::json(nullptr) : nlohmann::json(s.check.condition)},
                      {"points", ok ? s.path.points.size() : 0},
                      {"path_length_mm", s.path.length_mm},
                      {"max_step_mm", s.path.max_step_mm},
                      {"min_step_mm", s.path.min_step_mm},
                      {"smoothed", s.path.smoothed},
                      {"smoothing_rms_mm", s.path.smoothing_rms_mm},
                      {"leg_faces", r.leg_faces},
                      {"stub_faces", r.stub_faces},
                      {"segments", s.segments},
                      {"curve_vertices", s.curve_vertices},
                      {"candidate_pairs", s.candidate_pairs},
                      {"dropped_vertices", s.dropped_vertices},
                      {"intersection_s", s.intersection_seconds},
                      {"total_s", s.total_seconds},
                      {"written", r.written},
                      {"leg_marker_residuals_mm", r.leg_marker_residuals_mm},
                      {"stub_marker_residuals_mm", r.stub_marker_residuals_mm}};
  if (!ok) {
    j["where_mm"] = {s.check.where.x(), s.check.where.y(), s.check.where.z()};
    j["where_azimuth_deg"] = degrees(s.check.azimuth_rad);
  }
  add_robustness(r, &j);
  j["cad"] = cad_json(r.cad_inputs);
  return j;
}

}  // namespace conform
