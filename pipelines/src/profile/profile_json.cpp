#include "conform/pipelines/profile/profile_json.h"

#include "conform/core/error.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {
namespace {

nlohmann::json residual_json(const ProfileEdgeResidual& r) {
  if (!r.fitted) return nullptr;
  return {{"rms_mm", r.rms_mm}, {"max_mm", r.max_mm}, {"max_index", r.max_index}};
}

}  // namespace

ProfileJobOptions profile_job_options(const ProfileRequest& request) {
  ProfileJobOptions options;
  options.edge_path = request.edge_path;
  options.features_path = request.features_path;
  options.second_edge_path = request.second_edge_path;
  options.out_path = request.out_path;
  ProfileCompensationOptions& c = options.compensation;
  if (!parse_profile_edge_model(request.model, &c.edge.model)) {
    throw Error("--model: " + request.model + " not in {auto, cubic, spline}");
  }
  if (request.direction != "forward" && request.direction != "reverse") {
    throw Error("--direction: " + request.direction + " not in {forward, reverse}");
  }
  const bool second_edge = !request.second_edge_path.empty();
  if (request.web_plane && second_edge) throw Error("--web-plane excludes --second-edge");
  if (request.web_normal) {
    if (request.web_plane || second_edge) throw Error("--web-normal excludes --web-plane and --second-edge");
    const Eigen::Vector3d& z = *request.web_normal;
    if (!(z.norm() > 0.0) || !z.allFinite()) throw Error("--web-normal: the web normal must be finite and not zero");
    if (z.normalized() != Eigen::Vector3d::UnitZ()) c.web_normal = z;
  }
  c.fit_web_plane = request.web_plane;
  c.web_width_mm = request.web_width_mm;
  c.reversed = request.direction == "reverse";
  c.edge.knot_spacing_mm = request.knot_spacing_mm;
  c.edge.outlier_threshold_sigma = request.outlier_sigma;
  c.sampling.chord_tolerance_mm = request.chord_tolerance_mm;
  c.edge.points.max_gap_mm = request.max_gap_mm;
  c.edge.noise_mm = request.noise_mm;
  return options;
}

nlohmann::json profile_json(const ProfileJobOptions& options, const ProfileJobResult& job) {
  const ProfileCompensationResult& r = job.compensation;
  nlohmann::json features = nlohmann::json::array();
  for (const ProfileFeatureResult& f : r.features) {
    features.push_back({{"id", f.id},
                        {"type", to_string(f.type)},
                        {"points", f.mapped.size()},
                        {"centre_mm", f.has_centre ? json_of(f.centre) : nlohmann::json(nullptr)},
                        {"cubic_deviation_max_mm", f.cubic_deviation_max_mm},
                        {"gap_mm", f.gap_mm},
                        {"twist_mm_per_deg", f.twist_mm_per_deg},
                        {"warnings", f.warnings}});
  }
  return {{"edge_rms_mm", r.edge.rms_mm},
          {"edge_max_mm", r.edge.max_mm},
          {"model", to_string(r.edge.model)},
          {"model_selection", r.edge.selection},
          {"cubic_fit", residual_json(r.edge.cubic_fit)},
          {"spline_fit", residual_json(r.edge.spline_fit)},
          {"edge_points", job.edge_points},
          {"edge_length_mm", r.edge.curve.length_mm()},
          {"edge_spacing_median_mm", r.edge.points.median_spacing_mm},
          {"edge_gap_max_mm", r.edge.points.max_gap_mm},
          {"noise_mm", r.edge.noise_mm},
          {"edge_duplicates_dropped", r.edge.duplicates_dropped},
          {"edge_reordered", r.edge.points.reordered},
          {"edge_outliers", r.edge.outliers},
          {"edge_outlier_indices", r.edge.outlier_indices},
          {"reweighting_passes", r.edge.reweighting_passes},
          {"knot_spacing_mm", r.edge.knot_spacing_mm},
          {"smoothing_converged", r.edge.smoothing_converged},
          {"reversed", options.compensation.reversed},
          {"web", r.web_source},
          {"web_tilt_deg", r.local_web ? nlohmann::json(nullptr) : nlohmann::json(r.web_tilt_deg)},
          {"warnings", r.warnings},
          {"web_normal", r.local_web ? nlohmann::json(nullptr) : json_of(r.web_normal)},
          {"second_edge_points", job.second_edge_points},
          {"web_width_min_mm", r.local_web ? nlohmann::json(r.web_width_min_mm) : nlohmann::json(nullptr)},
          {"web_width_max_mm", r.local_web ? nlohmann::json(r.web_width_max_mm) : nlohmann::json(nullptr)},
          {"mapped_points", r.mapped_points},
          {"arc_length_residual_max_mm", r.arc_length_residual_max_mm},
          {"cubic_deviation_max_mm", r.cubic_deviation_max_mm},
          {"ok", r.ok},
          {"termination", r.termination},
          {"features", features},
          {"out", json_path_or_null(job.out_path)}};
}

}  // namespace conform
