#include "conform/datasets/tube_json.h"

#include <cmath>

#include "conform/core/constants.h"

namespace conform {

namespace {

using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json matrix_rows(const Eigen::Isometry3d& T) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return rows;
}

json geometry_json(const TubeTruth& t) {
  const TubeOptions& o = t.options;
  const double half = 0.5 * o.length_mm;
  return {{"radius_mm", t.radius_mm},
          {"diameter_mm", 2.0 * t.radius_mm},
          {"length_mm", o.length_mm},
          {"arc_deg", degrees(t.grid.closed ? 2.0 * M_PI : o.arc_rad)},
          {"arc_center_deg", degrees(o.arc_center_rad)},
          {"closed", t.grid.closed},
          {"surface", o.surface == TubeSurface::kOuter ? "outer" : "inner"},
          {"T_world_tube", matrix_rows(t.T_world_tube)},
          {"axis_point_mm", vec(t.axis_point)},
          {"axis_direction", vec(t.axis_direction)},
          {"axis_start_mm", vec(t.T_world_tube * Eigen::Vector3d(0.0, 0.0, -half))},
          {"axis_end_mm", vec(t.T_world_tube * Eigen::Vector3d(0.0, 0.0, half))}};
}

json mesh_json(const TubeScan& scan) {
  const TubeGrid& g = scan.truth.grid;
  return {{"edge_mm", g.edge_mm},
          {"vertex_count_requested", scan.truth.options.vertex_count},
          {"columns", g.columns},
          {"rows", g.rows},
          {"column_step_deg", degrees(g.column_step_rad)},
          {"column_step_mm", scan.truth.radius_mm * g.column_step_rad},
          {"row_step_mm", g.row_step_mm},
          {"vertices", scan.mesh.vertices.size()},
          {"faces", scan.mesh.faces.size()},
          {"vertex_normals", scan.mesh.has_normals()}};
}

json deformations_json(const TubeOptions& o) {
  json bumps = json::array();
  for (const TubeBump& b : o.bumps) {
    bumps.push_back({{"azimuth_deg", degrees(b.azimuth_rad)},
                     {"z_mm", b.z_mm},
                     {"height_mm", b.height_mm},
                     {"radius_mm", b.radius_mm}});
  }
  return {
      {"ovality", {{"amplitude_mm", o.ovality_mm}, {"azimuth_deg", degrees(o.ovality_azimuth_rad)}}},
      {"seam",
       {{"height_mm", o.seam_height_mm}, {"width_mm", o.seam_width_mm}, {"azimuth_deg", degrees(o.seam_azimuth_rad)}}},
      {"bumps", bumps},
      {"bow", {{"sagitta_mm", o.bow_mm}, {"azimuth_deg", degrees(o.bow_azimuth_rad)}}}};
}

// The standard deviation the noise has along one direction: the normal, or any axis when isotropic
// (uniform on [-a, a]: a / sqrt(3); uniform in a ball of radius a: a / sqrt(5)).
double noise_std(const TubeOptions& o) {
  if (o.noise_distribution == NoiseDistribution::kGaussian) return o.noise_mm;
  return o.noise_mm / std::sqrt(o.noise_direction == NoiseDirection::kNormal ? 3.0 : 5.0);
}

json effects_json(const TubeTruth& t) {
  const TubeOptions& o = t.options;
  json holes = json::array();
  for (std::size_t i = 0; i < t.holes.size(); ++i) {
    const TubeHole& h = t.holes[i];
    holes.push_back({{"azimuth_deg", degrees(h.azimuth_rad)},
                     {"z_mm", h.z_mm},
                     {"radius_mm", h.radius_mm},
                     {"random", i >= o.holes.size()}});
  }
  return {{"noise",
           {{"scale_mm", o.noise_mm},
            {"std_mm", noise_std(o)},
            {"distribution", o.noise_distribution == NoiseDistribution::kGaussian ? "gaussian" : "uniform"},
            {"direction", o.noise_direction == NoiseDirection::kNormal ? "normal" : "isotropic"}}},
          {"holes", holes},
          {"outliers",
           {{"fraction", o.outlier_fraction},
            {"distance_mm", o.outlier_distance_mm},
            {"count", t.outlier_indices.size()},
            {"indices", t.outlier_indices}}}};
}

}  // namespace

json tube_truth_json(const TubeScan& scan) {
  const TubeTruth& t = scan.truth;
  return {{"generator", "conform generate tube"},
          {"format_version", 1},
          {"seed", t.options.seed},
          {"conventions",
           "tube frame: z along the straight axis, the tube spans z in [-length/2, length/2] about axis_point; "
           "azimuth from the tube's x axis towards y; p_world = T_world_tube * p_tube; "
           "r(theta, z) = R + a cos 2(theta - theta0) + seam + bumps, then the cross-section moves by "
           "bow(z) = s (1 - (2z/L)^2) towards bow.azimuth; heights radial, positive away from the axis"},
          {"geometry", geometry_json(t)},
          {"mesh", mesh_json(scan)},
          {"deformations", deformations_json(t.options)},
          {"scanner", effects_json(t)}};
}

}  // namespace conform
