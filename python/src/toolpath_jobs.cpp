// conform._conform's path-planning jobs and a generator: profile, tube_joint, weld_layers, sicp, generate_tube
// (module.cpp has the measuring jobs). Keyword arguments are the CLI's flags; defaults come from the Options or Request
// structs.

#include <algorithm>
#include <array>
#include <initializer_list>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "conform/core/error.h"
#include "conform/pipelines/generate/generate_tube_json.h"
#include "conform/pipelines/profile/profile_json.h"
#include "conform/pipelines/profile/profile_report.h"
#include "conform/pipelines/sicp/sicp_json.h"
#include "conform/pipelines/sicp/sicp_report.h"
#include "conform/pipelines/tube_joint/tube_joint_json.h"
#include "conform/pipelines/tube_joint/tube_joint_report.h"
#include "conform/pipelines/weld_layers/weld_layers_json.h"
#include "conform/pipelines/weld_layers/weld_layers_report.h"
#include "job_report.h"

namespace conform::python {
namespace {

py::tuple job_weld_layers(const py::object& eroded, const py::object& reference, bool reference_from_border,
                          double bead_spacing, double layer_height, double chord_error, double torch_distance,
                          int layers, double depth_threshold, int outward, const std::string& bias, double min_coverage,
                          double min_crater_coverage, double bead_width, double max_overlap, const py::object& out,
                          const py::object& report) {
  const std::string report_path = report_path_of(report);
  WeldLayersJobOptions options;
  options.eroded_path = path_of(eroded);
  options.reference_path = path_of(reference);
  if (!options.reference_path.empty() && reference_from_border) {
    throw Error("weld-layers: give --reference FILE or --reference-from-border, not both");
  }
  if (options.reference_path.empty() && !reference_from_border) {
    throw Error("weld-layers: give --reference FILE or --reference-from-border");
  }
  if (layers < 0 || layers > kMaxWeldLayers) throw Error("layers: not in [0, " + std::to_string(kMaxWeldLayers) + "]");
  if (outward < -1 || outward > 1) throw Error("outward: not in [-1, 1]");
  if (bias != "check" && bias != "remove" && bias != "keep")
    throw Error("bias: " + bias + " not in {check, remove, keep}");
  options.weld.bead_spacing_mm = bead_spacing;
  options.weld.layer_height_mm = layer_height;
  options.weld.chord_error_mm = chord_error;
  options.weld.torch_distance_mm = torch_distance;
  options.weld.layers = layers;
  options.weld.depth_threshold_mm = depth_threshold;
  options.weld.outward_side = outward;
  options.weld.bias = bias == "remove" ? BiasMode::kRemove : bias == "keep" ? BiasMode::kKeep : BiasMode::kCheck;
  options.weld.min_coverage_pct = min_coverage;
  options.weld.min_crater_coverage_pct = min_crater_coverage;
  options.weld.bead_width_mm = bead_width;
  options.weld.max_overlap_mm = max_overlap;
  options.out_path = path_of(out);
  options.keep_geometry = !report_path.empty();
  CallFiles files({options.eroded_path, options.reference_path}, {options.out_path, report_path});
  const WeldLayersJobResult job = [&] {
    py::gil_scoped_release release;
    return run_weld_layers(options);
  }();
  if (!report_path.empty()) write_report(report_path, weld_layers_report(options, job));
  files.commit();
  // The CSV's rows (layer, path, point, normal), as arrays.
  std::vector<std::int32_t> layer, path;
  std::vector<Eigen::Vector3d> points, normals;
  for (const WeldPath& p : job.weld.paths) {
    layer.insert(layer.end(), p.points.size(), p.layer);
    path.insert(path.end(), p.points.size(), p.path);
    points.insert(points.end(), p.points.begin(), p.points.end());
    normals.insert(normals.end(), p.normals.begin(), p.normals.end());
  }
  py::dict arrays;
  arrays["layer"] = owned(std::move(layer));
  arrays["path"] = owned(std::move(path));
  arrays["points_mm"] = owned(std::move(points));
  arrays["normals"] = owned(std::move(normals));
  return answer(weld_layers_json(options, job), arrays);
}

py::tuple job_profile(const py::object& edge, const py::object& features, const std::string& model,
                      const std::optional<std::vector<double>>& web_normal, bool web_plane,
                      const py::object& second_edge, double web_width, const std::string& direction,
                      double knot_spacing, double outlier_sigma, double chord_tolerance, double max_gap, double noise,
                      const py::object& out, const py::object& report) {
  const std::string report_path = report_path_of(report);
  ProfileRequest request;
  request.edge_path = path_of(edge);
  request.features_path = path_of(features);
  request.second_edge_path = path_of(second_edge);
  request.out_path = path_of(out);
  request.model = model;
  if (web_normal) {
    if (web_normal->size() != 3) throw Error("web_normal: give three numbers x, y, z");
    request.web_normal = Eigen::Vector3d((*web_normal)[0], (*web_normal)[1], (*web_normal)[2]);
  }
  request.web_plane = web_plane;
  request.web_width_mm = web_width;
  request.direction = direction;
  request.knot_spacing_mm = knot_spacing;
  request.outlier_sigma = outlier_sigma;
  request.chord_tolerance_mm = chord_tolerance;
  request.max_gap_mm = max_gap;
  request.noise_mm = noise;
  ProfileJobOptions options = profile_job_options(request);
  options.keep_geometry = !report_path.empty();
  CallFiles files({request.edge_path, request.features_path, request.second_edge_path},
                  {request.out_path, report_path});
  const ProfileJobResult job = [&] {
    py::gil_scoped_release release;
    return run_profile(options);
  }();
  if (!report_path.empty()) write_report(report_path, profile_report(options, job));
  files.commit();
  // The CSV's rows: the feature (index into `features`), where to cut, the web normal, the cut direction.
  std::vector<std::int32_t> feature;
  std::vector<Eigen::Vector3d> points, normals, directions;
  for (std::size_t k = 0; k < job.compensation.features.size(); ++k) {
    const ProfileFeatureResult& f = job.compensation.features[k];
    feature.insert(feature.end(), f.mapped.size(), static_cast<std::int32_t>(k));
    points.insert(points.end(), f.mapped.begin(), f.mapped.end());
    normals.insert(normals.end(), f.normals.begin(), f.normals.end());
    directions.insert(directions.end(), f.directions.begin(), f.directions.end());
  }
  py::dict arrays;
  arrays["feature"] = owned(std::move(feature));
  arrays["points_mm"] = owned(std::move(points));
  arrays["normals"] = owned(std::move(normals));
  arrays["directions"] = owned(std::move(directions));
  return answer(profile_json(options, job), arrays);
}

// One number for both walls, or [leg, stub].
std::vector<double> walls_of(const py::object& value) {
  if (value.is_none()) return {};
  if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value)) return {value.cast<double>()};
  return value.cast<std::vector<double>>();
}

py::dict tube_joint_arrays(TubeJointSolution& s) {
  std::vector<double> phi;
  std::vector<Eigen::Vector3d> point, tangent, stub_normal, leg_normal, cut, weld;
  for (const PathFrame& f : s.frames) {
    phi.push_back(f.phi_rad);
    point.push_back(f.point);
    tangent.push_back(f.tangent);
    stub_normal.push_back(f.stub_normal);
    leg_normal.push_back(f.leg_normal);
  }
  for (const ToolPose& p : s.tools.cut) cut.push_back(p.direction);
  for (const ToolPose& p : s.tools.weld) weld.push_back(p.direction);
  py::dict arrays;
  arrays["warnings"] = py::cast(s.warnings);
  arrays["phi_rad"] = owned(std::move(phi));
  arrays["points_mm"] = owned(std::move(point));
  arrays["tangents"] = owned(std::move(tangent));
  arrays["stub_normals"] = owned(std::move(stub_normal));
  arrays["leg_normals"] = owned(std::move(leg_normal));
  arrays["cut_directions"] = owned(std::move(cut));
  arrays["weld_directions"] = owned(std::move(weld));
  arrays["groove_rad"] = owned(std::move(s.tools.groove_rad));
  arrays["psi_rad"] = owned(std::move(s.tools.psi_rad));
  return arrays;
}

py::tuple job_tube_joint(const py::object& leg, const py::object& stub, const py::kwargs& kw) {
  TubeJointRequest request;
  TubeJointJobOptions& o = request.job;
  Inputs inputs;
  o.leg_path = inputs.geometry(leg, "leg");
  o.stub_path = inputs.geometry(stub, "stub");
  const auto take = [&kw](const char* name) -> py::object {
    return kw.contains(name) ? py::object(kw[name]) : py::object(py::none());
  };
  const auto set = [&take](const char* name, auto& field) {
    const py::object v = take(name);
    if (!v.is_none()) field = v.cast<std::remove_reference_t<decltype(field)>>();
  };
  static const char* const known[] = {"pitch_deg",        "offset",
                                      "protrusion",       "leg_pose",
                                      "leg_markers",      "stub_markers",
                                      "marker_tolerance", "backtrack_tolerance",
                                      "max_facet_error",  "island_ratio",
                                      "wall_thickness",   "step_deg",
                                      "step_mm",          "smoothing",
                                      "smoothing_rms",    "groove_deg",
                                      "groove_table",     "groove_interpolation",
                                      "weld_angle_deg",   "cut_standoff",
                                      "weld_standoff",    "k_normals",
                                      "k_refine",         "out_path",
                                      "out_cut",          "out_weld",
                                      "report",           "progress",
                                      "cad_deflection",   "cad_angle_deg",
                                      "cad_save_mesh",    "max_direction_error",
                                      "weld_tolerance"};
  for (const auto& item : kw) {
    const std::string name = py::str(item.first);
    if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return name == k; }) == std::end(known)) {
      throw py::type_error("tube_joint() got an unexpected keyword argument '" + name + "'");
    }
  }
  if (!take("pitch_deg").is_none()) request.pitch_deg = take("pitch_deg").cast<double>();
  set("offset", o.spec.offset_mm);
  request.protrusion_given = !take("protrusion").is_none();
  set("protrusion", o.spec.protrusion_mm);
  o.leg_pose_path = inputs.transform(take("leg_pose"), "leg_pose");
  o.leg_markers_path = path_of(take("leg_markers"));
  o.stub_markers_path = path_of(take("stub_markers"));
  set("marker_tolerance", o.marker_tolerance_mm);
  set("backtrack_tolerance", o.solve.backtrack_tolerance_mm);
  set("max_facet_error", o.solve.max_facet_error_mm);
  set("island_ratio", o.solve.max_island_ratio);
  request.walls_mm = walls_of(take("wall_thickness"));
  set("step_deg", request.step_deg);
  if (!take("step_mm").is_none()) request.step_mm = take("step_mm").cast<double>();
  set("smoothing", request.smoothing_mm2);
  set("smoothing_rms", request.smoothing_rms_mm);
  if (!take("groove_deg").is_none()) request.groove_deg = take("groove_deg").cast<std::array<double, 4>>();
  request.groove_table_path = path_of(take("groove_table"));
  set("groove_interpolation", request.interpolation);
  set("weld_angle_deg", request.weld_angle_deg);
  set("cut_standoff", o.solve.tools.cut_standoff_mm);
  set("weld_standoff", o.solve.tools.weld_standoff_mm);
  set("k_normals", o.solve.geometry.k_normals);
  set("k_refine", o.solve.geometry.k_refine);
  set("max_direction_error", o.solve.max_direction_error_deg);
  set("weld_tolerance", o.solve.weld_edge_fraction);
  o.out_path = path_of(take("out_path"));
  o.out_cut = path_of(take("out_cut"));
  o.out_weld = path_of(take("out_weld"));
  set_cad_options(take("cad_deflection"), take("cad_angle_deg"), take("cad_save_mesh"), o.cad);
  const std::string report_path = report_path_of(take("report"));
  TubeJointJobOptions options = tube_joint_job_options(request);
  options.keep_geometry = !report_path.empty();
  const Progress progress(take("progress"));
  options.solve.progress = progress.function();
  CallFiles files(
      {o.leg_path, o.stub_path, o.leg_pose_path, o.leg_markers_path, o.stub_markers_path, request.groove_table_path},
      {o.out_path, o.out_cut, o.out_weld, report_path, o.cad.save_mesh_path});
  TubeJointJobResult job = released(progress, [&] { return run_tube_joint(options); });
  if (!report_path.empty()) write_report(report_path, tube_joint_report(options, job));
  files.commit();
  return answer(tube_joint_json(job), tube_joint_arrays(job.solution));
}

Eigen::Vector3d vector_of(const py::handle& value) {
  const std::array<double, 3> v = value.cast<std::array<double, 3>>();
  return {v[0], v[1], v[2]};
}

py::tuple job_generate_tube(const py::object& out, const py::kwargs& kw) {
  check_keywords("generate_tube", kw,
                 {"radius",
                  "length",
                  "arc_deg",
                  "arc_center_deg",
                  "inner",
                  "edge",
                  "vertices",
                  "axis_point",
                  "axis_direction",
                  "azimuth_reference",
                  "ovality",
                  "ovality_azimuth_deg",
                  "seam_height",
                  "seam_width",
                  "seam_azimuth_deg",
                  "bump",
                  "bow",
                  "bow_azimuth_deg",
                  "noise",
                  "noise_type",
                  "noise_direction",
                  "hole",
                  "holes",
                  "hole_radius",
                  "outliers",
                  "outlier_distance",
                  "seed",
                  "ascii",
                  "double",
                  "normals",
                  "progress"});
  GenerateTubeRequest r;
  r.out_path = path_of(out);
  const auto set = [&kw](const char* name, auto& field) {
    if (kw.contains(name) && !py::object(kw[name]).is_none()) {
      field = py::object(kw[name]).cast<std::remove_reference_t<decltype(field)>>();
    }
  };
  if (kw.contains("edge") && kw.contains("vertices")) throw Error("edge excludes vertices: give one");
  set("radius", r.tube.radius_mm);
  set("length", r.tube.length_mm);
  set("arc_deg", r.arc_deg);
  set("arc_center_deg", r.arc_center_deg);
  set("inner", r.inner);
  set("edge", r.tube.edge_mm);
  set("vertices", r.tube.vertex_count);
  if (kw.contains("axis_point")) r.axis_point = vector_of(kw["axis_point"]);
  if (kw.contains("axis_direction")) r.axis_direction = vector_of(kw["axis_direction"]);
  if (kw.contains("azimuth_reference")) r.azimuth_reference = vector_of(kw["azimuth_reference"]);
  set("ovality", r.tube.ovality_mm);
  set("ovality_azimuth_deg", r.ovality_azimuth_deg);
  set("seam_height", r.tube.seam_height_mm);
  set("seam_width", r.tube.seam_width_mm);
  set("seam_azimuth_deg", r.seam_azimuth_deg);
  set("bump", r.bumps);
  set("bow", r.tube.bow_mm);
  set("bow_azimuth_deg", r.bow_azimuth_deg);
  set("noise", r.tube.noise_mm);
  set("noise_type", r.noise_type);
  set("noise_direction", r.noise_direction);
  set("hole", r.holes);
  set("holes", r.tube.random_holes);
  set("hole_radius", r.tube.random_hole_radius_mm);
  set("outliers", r.tube.outlier_fraction);
  set("outlier_distance", r.tube.outlier_distance_mm);
  set("seed", r.seed);
  set("ascii", r.ascii);
  set("double", r.double_precision);
  set("normals", r.normals);
  GenerateTubeOptions options = generate_tube_options(r);
  const Progress progress(kw.contains("progress") ? py::object(kw["progress"]) : py::object(py::none()));
  options.tube.progress = progress.function();
  CallFiles files({}, {r.out_path});
  const GenerateTubeResult result = released(progress, [&] { return run_generate_tube(options); });
  files.commit();
  return answer(generate_tube_json(result), py::dict());
}

// `conform sicp`: the flags as keyword arguments, unset ones keep SicpJobOptions' defaults.
py::tuple job_sicp(const py::object& contour, const py::object& scan, const py::object& trajectory,
                   const py::kwargs& kw) {
  check_keywords("sicp", kw,
                 {"surface",          "segment_length",  "overlap",        "curvature_radius", "model",
                  "projection_fit",   "neighbourhood",   "stability",      "max_distance",     "coarse_max_distance",
                  "scan_voxel",       "no_joint",        "joint_weight",   "joint_damping",    "max_iterations",
                  "min_edge_points",  "edge_radius",     "max_edge_gap",   "outlier_ratio",    "max_offset",
                  "normal_smoothing", "normals",         "truth",          "out_trajectory",   "out_rows",
                  "report",           "progress",        "cad_deflection", "cad_angle_deg",    "cad_save_mesh",
                  "max_corner_gap",   "max_edge_offset", "max_row_step",   "max_off_surface",  "max_surface_offset",
                  "max_normal_error_deg", "max_local_offset", "max_dent_slope_deg"});
  const auto take = [&kw](const char* name) {
    return kw.contains(name) ? py::object(kw[name]) : py::object(py::none());
  };
  const auto set = [&take](const char* name, auto& field) {
    const py::object v = take(name);
    if (!v.is_none()) field = v.cast<std::remove_reference_t<decltype(field)>>();
  };
  Inputs inputs;
  SicpJobOptions options;
  options.contour_path = path_of(contour);  // a CSV polyline or a mesh whose boundary is taken: a path
  options.scan_path = inputs.geometry(scan, "scan");
  options.trajectory_path = path_of(trajectory);
  options.surface_path = inputs.geometry(take("surface"), "surface");
  options.truth_path = path_of(take("truth"));
  options.out_trajectory_path = path_of(take("out_trajectory"));
  options.out_rows_path = path_of(take("out_rows"));
  set_cad_options(take("cad_deflection"), take("cad_angle_deg"), take("cad_save_mesh"), options.cad);
  const std::string report_path = report_path_of(take("report"));
  options.keep_geometry = !report_path.empty();
  SicpCompensationOptions& o = options.compensation;
  std::string model = "sicp", fit = "parabola", normals = o.normals.from_scan ? "scan" : "rotate";
  bool no_joint = false;
  set("model", model);
  set("projection_fit", fit);
  set("normals", normals);
  set("no_joint", no_joint);
  set_sicp_choices(model, fit, normals, &o);
  o.sicp.joint_refinement = !no_joint;
  set("segment_length", o.sicp.segmentation.segment_length_mm);
  set("overlap", o.sicp.segmentation.overlap);
  set("curvature_radius", o.sicp.segmentation.curvature_radius_mm);
  set("neighbourhood", o.sicp.neighbourhood_mm);
  set("stability", o.sicp.stability_mm);
  set("max_distance", o.sicp.max_distance_mm);
  set("coarse_max_distance", o.sicp.coarse_max_distance_mm);
  set("scan_voxel", o.sicp.scan_voxel_mm);
  set("joint_weight", o.sicp.joint.weight);
  set("joint_damping", o.sicp.joint.damping);
  set("max_iterations", o.sicp.max_iterations);
  if (o.sicp.max_iterations < 1 || o.sicp.max_iterations > 1000) throw Error("max_iterations: not in [1, 1000]");
  set("min_edge_points", o.checks.min_edge_points);
  set("edge_radius", o.checks.edge_radius_mm);
  set("max_edge_gap", o.checks.max_edge_gap_mm);
  set("outlier_ratio", o.checks.outlier_ratio);
  set("max_offset", o.checks.max_offset_mm);
  set("max_corner_gap", o.checks.max_corner_gap_mm);
  set("max_edge_offset", o.checks.max_edge_offset_mm);
  set("max_row_step", o.checks.max_row_step_mm);
  set("max_off_surface", o.checks.max_off_surface);
  set("max_surface_offset", o.checks.max_surface_offset_mm);
  set("max_normal_error_deg", o.checks.max_normal_error_deg);
  set("max_local_offset", o.checks.max_local_offset_mm);
  set("max_dent_slope_deg", o.checks.max_dent_slope_deg);
  set("normal_smoothing", o.normals.smooth_mm);
  const Progress progress(take("progress"));
  options.progress = progress.function();
  CallFiles files(
      {options.contour_path, options.scan_path, options.trajectory_path, options.surface_path, options.truth_path},
      {options.out_trajectory_path, options.out_rows_path, report_path, options.cad.save_mesh_path});
  SicpJobResult result = released(progress, [&] { return run_sicp(options); });
  if (!report_path.empty()) write_report(report_path, sicp_report(options, result));
  files.commit();
  const nlohmann::json j = sicp_json(result);
  // The compensated trajectory only when it can be trusted (the CLI writes it only then): empty otherwise.
  Trajectory& t = result.compensation.trajectory;
  if (!result.compensation.trusted) t = Trajectory{};
  py::dict arrays;
  arrays["warnings"] = py::cast(result.warnings);
  arrays["points_mm"] = owned(std::move(t.points));
  arrays["normals"] = owned(std::move(t.normals));
  return answer(j, arrays);
}

}  // namespace

void bind_toolpath_jobs(py::module_& m) {
  using py::arg;
  const WeldLayerOptions weld;
  m.def("weld_layers", &job_weld_layers, arg("eroded"), py::kw_only(), arg("reference") = py::none(),
        arg("reference_from_border") = false, arg("bead_spacing"), arg("layer_height"), arg("chord_error"),
        arg("torch_distance") = weld.torch_distance_mm, arg("layers") = weld.layers,
        arg("depth_threshold") = weld.depth_threshold_mm, arg("outward") = weld.outward_side, arg("bias") = "check",
        arg("min_coverage") = weld.min_coverage_pct, arg("min_crater_coverage") = weld.min_crater_coverage_pct,
        arg("bead_width") = weld.bead_width_mm, arg("max_overlap") = weld.max_overlap_mm, arg("out") = py::none(),
        arg("report") = py::none());
  const ProfileRequest profile;
  m.def("profile", &job_profile, arg("edge"), arg("features"), py::kw_only(), arg("model") = profile.model,
        arg("web_normal") = py::none(), arg("web_plane") = profile.web_plane, arg("second_edge") = py::none(),
        arg("web_width") = profile.web_width_mm, arg("direction") = profile.direction,
        arg("knot_spacing") = profile.knot_spacing_mm, arg("outlier_sigma") = profile.outlier_sigma,
        arg("chord_tolerance") = profile.chord_tolerance_mm, arg("max_gap") = profile.max_gap_mm,
        arg("noise") = profile.noise_mm, arg("out") = py::none(), arg("report") = py::none());
  // Keyword arguments as the CLI's flags (tube_joint_json.h's TubeJointRequest holds their defaults); see
  // conform.tube_joint in __init__.py for the list.
  m.def("tube_joint", &job_tube_joint, arg("leg"), arg("stub"));
  // Keyword arguments as the flags of `conform generate tube` (GenerateTubeRequest holds their defaults).
  m.def("generate_tube", &job_generate_tube, arg("out"));
  // Keyword arguments as the flags of `conform sicp` (SicpJobOptions holds their defaults).
  m.def("sicp", &job_sicp, arg("contour"), arg("scan"), arg("trajectory"));
}

}  // namespace conform::python
