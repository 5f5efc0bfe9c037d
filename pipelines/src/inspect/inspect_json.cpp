#include "conform/pipelines/inspect/inspect_json.h"

#include <cmath>

#include "conform/core/constants.h"
#include "conform/pipelines/common/cad_json.h"
#include "conform/pipelines/common/json_values.h"

namespace conform {

namespace {

nlohmann::json number_or_null(bool has, double value) {
  return has && std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json nominal_json(const CadFace& f) {
  nlohmann::json j = {{"type", to_string(f.type)}, {"area_mm2", f.area_mm2}, {"centre_mm", json_of(f.centre_mm)}};
  switch (f.type) {
    case CadSurfaceType::kPlane:
      j["point_mm"] = json_of(f.origin_mm);
      j["normal"] = json_of(f.axis);
      break;
    case CadSurfaceType::kCylinder:
      j["axis_point_mm"] = json_of(f.origin_mm);
      j["axis"] = json_of(f.axis);
      j["radius_mm"] = f.radius_mm;
      j["hole"] = f.sense < 0;
      break;
    case CadSurfaceType::kCone:
      j["apex_mm"] = json_of(f.origin_mm);
      j["axis"] = json_of(f.axis);
      j["half_angle_deg"] = degrees(f.half_angle_rad);
      j["hole"] = f.sense < 0;
      break;
    case CadSurfaceType::kSphere:
      j["centre_of_sphere_mm"] = json_of(f.origin_mm);
      j["radius_mm"] = f.radius_mm;
      j["hole"] = f.sense < 0;
      break;
    case CadSurfaceType::kTorus:
      j["centre_of_torus_mm"] = json_of(f.origin_mm);
      j["axis"] = json_of(f.axis);
      j["major_radius_mm"] = f.radius_mm;
      j["minor_radius_mm"] = f.minor_radius_mm;
      j["hole"] = f.sense < 0;
      break;
    default:
      break;
  }
  return j;
}

// A face's or feature's figures at the best fit: its JSON less what does not depend on the pose.
nlohmann::json best_fit_figures(nlohmann::json j) {
  for (const char* key : {"id", "type", "deviation_to", "form_trim", "nominal", "tolerance", "kind", "faces",
                          "nominal_diameter_mm", "nominal_radius_mm", "nominal_half_angle_deg",
                          "nominal_minor_radius_mm"}) {
    j.erase(key);
  }
  return j;
}

}  // namespace

const char* best_fit_pose_name(const std::string& alignment) {
  if (alignment == "best-fit") return "the initial best fit (--align best-fit)";
  if (alignment == "transform") return "point-to-surface ICP from the transform";
  return "--align best-fit on the scan as read";
}

nlohmann::json face_json(const FaceInspection& f) {
  const bool seen = f.points > 0;
  nlohmann::json j = {{"id", f.id},
                      {"type", to_string(f.nominal.type)},
                      {"points", f.points},
                      {"deviation_to", f.exact ? "exact surface" : "mesh"},
                      {"centroid_mm", json_of(f.centroid_mm, !seen)},
                      {"mean_mm", number_or_null(seen, f.deviation.mean_mm)},
                      {"std_mm", number_or_null(seen, f.deviation.std_mm)},
                      {"min_mm", number_or_null(seen, f.deviation.min_mm)},
                      {"max_mm", number_or_null(seen, f.deviation.max_mm)},
                      {"form_mm", number_or_null(f.form_measured, f.form.width_mm)},
                      {"form_full_mm", number_or_null(f.form_measured, f.form.full_width_mm)},
                      {"form_reference", f.form_measured ? nlohmann::json(f.form_reference) : nlohmann::json(nullptr)},
                      {"form_trim", f.form.trim_share},
                      {"fitted", f.fitted},
                      {"fit_note", f.fit_note.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.fit_note)},
                      {"nominal", nominal_json(f.nominal)}};
  if (f.verdict) {
    const FaceVerdict& v = *f.verdict;
    const auto limit = [](const std::optional<double>& x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
    j["tolerance"] = {{"lower_mm", limit(v.tolerance.lower_mm)},
                      {"upper_mm", limit(v.tolerance.upper_mm)},
                      {"form_mm", limit(v.tolerance.form_mm)},
                      {"measured", v.measured},
                      {"profile_pass", v.measured ? nlohmann::json(v.profile_pass) : nlohmann::json(nullptr)},
                      {"form_pass", v.measured ? nlohmann::json(v.form_pass) : nlohmann::json(nullptr)},
                      {"pass", v.measured ? nlohmann::json(v.pass) : nlohmann::json(nullptr)}};
  }
  if (f.nominal.type == CadSurfaceType::kCylinder) {
    j["nominal_radius_mm"] = f.nominal.radius_mm;
    j["radius_mm"] = number_or_null(f.fitted, f.radius_mm);
    j["radius_std_mm"] = number_or_null(f.fitted, f.radius_std_mm);
    j["axis"] = json_of(f.axis, !f.fitted);
    j["axis_point_mm"] = json_of(f.axis_point_mm, !f.fitted);
    j["axis_offset_mm"] = number_or_null(f.fitted, f.axis_offset_mm);
    j["axis_angle_deg"] = number_or_null(f.fitted, f.axis_angle_deg);
    j["length_mm"] = number_or_null(f.fitted, f.length_mm);
    j["diameter_mm"] = number_or_null(f.fitted, 2.0 * f.radius_mm);
    j["position_mm"] = number_or_null(f.fitted, f.position_mm);
    j["perpendicularity_mm"] = number_or_null(f.fitted, f.perpendicularity_mm);
  }
  if (f.nominal.type == CadSurfaceType::kSphere) {
    j["nominal_radius_mm"] = f.nominal.radius_mm;
    j["radius_mm"] = number_or_null(f.fitted, f.radius_mm);
    j["centre_mm"] = json_of(f.centre_mm, !f.fitted);
    j["centre_offset_mm"] = number_or_null(f.fitted, f.centre_offset_mm);
  }
  if (f.nominal.type == CadSurfaceType::kCone) {
    j["nominal_half_angle_deg"] = degrees(f.nominal.half_angle_rad);
    j["half_angle_deg"] = number_or_null(f.fitted, f.half_angle_deg);
    j["apex_mm"] = json_of(f.apex_mm, !f.fitted);
    j["axis"] = json_of(f.axis, !f.fitted);
    j["axis_point_mm"] = json_of(f.axis_point_mm, !f.fitted);
    j["axis_offset_mm"] = number_or_null(f.fitted, f.axis_offset_mm);
    j["axis_angle_deg"] = number_or_null(f.fitted, f.axis_angle_deg);
    j["radius_mm"] = number_or_null(f.fitted, f.radius_mm);
    j["nominal_radius_mm"] = number_or_null(f.fitted, f.nominal_radius_mm);
  }
  if (f.nominal.type == CadSurfaceType::kTorus) {
    j["nominal_radius_mm"] = f.nominal.radius_mm;
    j["nominal_minor_radius_mm"] = f.nominal.minor_radius_mm;
    j["radius_mm"] = number_or_null(f.fitted, f.radius_mm);
    j["minor_radius_mm"] = number_or_null(f.fitted, f.minor_radius_mm);
    j["centre_mm"] = json_of(f.centre_mm, !f.fitted);
    j["centre_offset_mm"] = number_or_null(f.fitted, f.centre_offset_mm);
    j["axis"] = json_of(f.axis, !f.fitted);
    j["axis_angle_deg"] = number_or_null(f.fitted, f.axis_angle_deg);
  }
  if (f.nominal.type == CadSurfaceType::kPlane) {
    j["normal"] = json_of(f.normal, !f.fitted);
    j["angle_to_nominal_deg"] = number_or_null(f.fitted, f.angle_to_nominal_deg);
    j["plane_offset_mm"] = number_or_null(f.fitted, f.plane_offset_mm);
  }
  return j;
}

nlohmann::json feature_json(const FeatureInspection& f) {
  nlohmann::json j = face_json(f.measured);
  j["kind"] = f.measured.nominal.sense < 0 ? "hole" : "boss";
  j["faces"] = f.faces;
  j["nominal_diameter_mm"] = 2.0 * f.measured.nominal.radius_mm;
  if (f.verdict) {
    const FeatureVerdict& v = *f.verdict;
    const auto limit = [](const std::optional<double>& x) { return x ? nlohmann::json(*x) : nlohmann::json(nullptr); };
    const auto verdict = [&](bool pass) { return v.measured ? nlohmann::json(pass) : nlohmann::json(nullptr); };
    j["tolerance"] = {{"face", v.tolerance.face_id},
                      {"diameter_lower_mm", limit(v.tolerance.diameter_lower_mm)},
                      {"diameter_upper_mm", limit(v.tolerance.diameter_upper_mm)},
                      {"position_mm", limit(v.tolerance.position_mm)},
                      {"measured", v.measured},
                      {"size_pass", verdict(v.size_pass)},
                      {"position_pass", verdict(v.position_pass)},
                      {"pass", verdict(v.pass)}};
  }
  return j;
}

nlohmann::json inspect_json(const InspectOptions& options, const InspectResult& r, const std::string& units) {
  const InspectBestFit& best = r.best_fit;
  const bool beside = best.computed && best.converged;
  nlohmann::json faces = nlohmann::json::array();
  for (std::size_t k = 0; k < r.faces.size(); ++k) {
    faces.push_back(face_json(r.faces[k]));
    if (best.computed) faces.back()["best_fit"] = beside ? best_fit_figures(face_json(best.faces[k])) : nullptr;
  }
  nlohmann::json features = nlohmann::json::array();
  for (std::size_t k = 0; k < r.features.size(); ++k) {
    features.push_back(feature_json(r.features[k]));
    if (best.computed) {
      features.back()["best_fit"] = beside ? best_fit_figures(feature_json(best.features[k])) : nullptr;
    }
  }
  nlohmann::json j = {{"scan", options.scan_path},
                      {"reference", options.reference_path},
                      {"transform", json_path_or_null(options.transform_path)},
                      {"alignment", r.alignment},
                      {"T_ref_scan", json_of(r.T_ref_scan)},
                      {"units", units},
                      {"ok", r.ok},
                      {"termination", r.termination},
                      {"points", r.scan_points},
                      {"assigned", r.assigned},
                      {"unassigned_beyond_distance", r.beyond_distance},
                      {"unassigned_normal_mismatch", r.normal_mismatch},
                      {"scan_noise_mm", r.scan_noise_mm},
                      {"max_distance_mm", r.max_distance_mm},
                      {"max_distance_automatic", r.max_distance_automatic},
                      {"max_normal_angle_deg", degrees(options.max_normal_angle_rad)},
                      {"form_definition",
                       "width of the zone about the least-squares feature (plane, cylinder, cone, sphere, torus; "
                       "else, or where the fit fails, the nominal surface) "
                       "holding all but form_trim of the residuals, half trimmed at each end; form_full_mm untrimmed"},
                      {"faces", faces},
                      {"features", features},
                      {"out_faces", json_path_or_null(r.out_faces_path)}};
  if (!options.datum_faces.empty()) {
    j["datums"] = {{"faces", options.datum_faces},
                   {"T_datum_initial", json_of(r.T_datum_initial)},
                   {"moved_mm", r.datum_moved_mm},
                   {"rotation_deg", degrees(Eigen::AngleAxisd(r.T_datum_initial.linear()).angle())}};
    j["best_fit"] = {{"pose", best_fit_pose_name(r.alignment)},
                     {"converged", best.converged},
                     {"T_ref_scan", beside ? json_of(best.T_ref_scan) : nlohmann::json(nullptr)},
                     {"assigned", beside ? nlohmann::json(best.assigned) : nlohmann::json(nullptr)},
                     {"displacement_mm", number_or_null(beside, best.displacement_mm)},
                     {"angle_deg", number_or_null(beside, best.angle_deg)}};
  } else {
    j["datums"] = nullptr;
  }
  j["tolerances"] = json_path_or_null(options.tolerances_path);
  j["verdict"] = r.verdict.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.verdict);
  if (r.alignment == "best-fit") {
    j["align_trust"] = r.align_trust;
    j["align_summary"] = r.align_summary;
  }
  j["cad"] = cad_json(r.cad_inputs);
  return j;
}

}  // namespace conform
