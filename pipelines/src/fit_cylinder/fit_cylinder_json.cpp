#include "conform/pipelines/fit_cylinder/fit_cylinder_json.h"

#include "conform/core/constants.h"
#include "conform/pipelines/common/cad_json.h"

#include "conform/pipelines/common/json_values.h"

namespace conform {
nlohmann::json fit_cylinder_json(const FitCylinderJobResult& job) {
  const CylinderFitResult& f = job.fit;
  nlohmann::json j = {{"input", job.input_path},
          {"points", job.points},
          {"fitted_points", job.surface_points ? "surface samples" : "vertices"},
          {"normals", to_string(job.normals)},
          {"ok", f.ok},
          {"converged", f.converged},
          {"failure", to_string(f.failure)},
          {"termination", f.termination},
          {"axis_point_mm", json_of(f.cylinder.axis_point)},
          {"axis_direction", json_of(f.cylinder.axis_direction)},
          {"radius_mm", f.cylinder.radius_mm},
          {"rms_mm", f.rms_mm},
          {"inliers", f.inliers.size()},
          {"inlier_fraction", f.inlier_fraction},
          {"radius_std_mm", f.radius_std_mm},
          {"axis_angle_std_deg", degrees(f.axis_angle_std_rad)},
          {"axis_point_std_mm", f.axis_point_std_mm},
          {"noise_sigma_mm", f.noise_sigma_mm},
          {"threshold_mm", f.threshold_mm},
          {"arc_deg", degrees(f.arc_rad)},
          {"side", to_string(f.side)},
          {"shape_deviation_mm", f.shape_deviation_mm},
          {"hidden_ovality_mm", f.hidden_ovality_mm},
          {"shape_axis_ambiguity_mm", f.shape_axis_ambiguity_mm},
          {"shape_radius_ambiguity_mm", f.shape_radius_ambiguity_mm},
          {"warnings", job.warnings},
          {"ransac_iterations", f.ransac_iterations},
          {"refine_rounds", f.refine_rounds},
          {"solver_iterations", f.solver_iterations},
          {"out", json_path_or_null(job.out_path)}};
  j["cad"] = cad_json(job.cad_inputs);
  return j;
}

}  // namespace conform
