#include "conform/pipelines/tube_joint/tube_joint.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <cstdio>

#include "common/cad_inputs.h"
#include "conform/core/atomic_file.h"
#include "conform/core/constants.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/mesh_sampling.h"
#include "conform/core/mesh_weld.h"
#include "conform/core/output_set.h"
#include "conform/core/phong_surface.h"
#include "conform/core/transform_io.h"
#include "conform/registration/tube_reference.h"
#include "conform/toolpath/intersection/intersection_graph.h"

namespace conform {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Mesh posed(const Mesh& mesh, const Eigen::Isometry3d& T) {
  Mesh out;
  out.faces = mesh.faces;
  out.vertices.resize(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) out.vertices[i] = T * mesh.vertices[i];
  return out;
}

TubeJointSolution failed(TubeJointSolution solution, const CurveCheck& check) {
  solution.ok = false;
  solution.check = check;
  solution.termination = check.message;
  return solution;
}

// All or none (OutputSet): a path without its cut and weld poses is half an output.
void write_all(const std::vector<std::pair<std::string, std::string>>& files, std::vector<std::string>* written) {
  OutputSet outputs;
  for (const auto& [path, text] : files) {
    if (!path.empty()) write_file_atomically(path, text);
  }
  outputs.commit();
  for (const auto& [path, text] : files) {
    if (!path.empty()) written->push_back(path);
  }
}

}  // namespace

bool TubeJointSolveOptions::IsValid(std::string* error) const {
  std::string why;
  if (!intersection.IsValid(&why) || !sampling.IsValid(&why) || !geometry.IsValid(&why) || !tools.IsValid(&why) ||
      !safety.IsValid(&why)) {
  } else if (!std::isfinite(backtrack_tolerance_mm)) {
    why = "backtrack tolerance must be finite (< 0: automatic)";
  } else if (!(max_facet_error_mm > 0.0)) {
    why = "the largest facet error must be > 0 mm";
  } else if (!(max_island_ratio >= 0.0 && max_island_ratio < 1.0)) {
    why = "the island ratio must be in [0, 1)";
  } else if (!(max_direction_error_deg > 0.0 && max_direction_error_deg <= 90.0)) {
    why = "the largest direction error must be in (0, 90] deg";
  } else if (!(weld_edge_fraction >= 0.0 && weld_edge_fraction <= 0.25)) {
    why = "the weld tolerance must be in [0, 0.25] of the median edge";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

namespace {

void warn_coarse(const char* name, const ScanQuality& q, std::vector<std::string>* warnings) {
  if (q.edge_angle_deg <= TubeJointSolveOptions::kCoarseEdgeAngleDeg) return;
  std::ostringstream text;
  text.precision(3);
  text << "the " << name << " mesh is coarse for its curvature: its " << q.edge_mm << " mm edges turn the normals by "
       << q.edge_angle_deg << " deg each (radius of curvature " << 1.0 / q.curvature_per_mm
       << " mm); normals and refined points degrade, use edges under "
       << TubeJointSolveOptions::kCoarseEdgeAngleDeg / q.edge_angle_deg * q.edge_mm << " mm";
  warnings->push_back(text.str());
}

// A CAD tessellation's vertices lie on its faces' boundaries only (a cylinder's on its two rims, metres apart), but the
// normals and the refinement fit the k nearest vertices of each mesh (joint_geometry.h): points spread over its smooth
// surface (core/mesh_sampling.h) are added as vertices without faces, so that those neighbours are near. About one per
// 4 mm x 4 mm (k_normals = 40 of them then span about 14 mm, like a fine scan's), at most 2 million.
Mesh with_surface_points(Mesh mesh) {
  constexpr double kSpacingMm = 4.0;
  constexpr double kMostPoints = 2e6;
  double area = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) area += face_area(mesh, f);
  const double spacing = std::max(kSpacingMm, std::sqrt(area / kMostPoints));
  const auto count = static_cast<std::size_t>(std::ceil(area / (spacing * spacing)));
  if (count == 0) return mesh;
  const PhongSurface smooth(mesh);
  const MeshSurfaceSample sample = sample_mesh_surface(mesh, count, &smooth);
  mesh.normals.clear();
  mesh.vertices.insert(mesh.vertices.end(), sample.points.begin(), sample.points.end());
  return mesh;
}

// The path figures of the points written (after refinement).
void measure_written_path(const std::vector<PathFrame>& frames, SampledPath* path) {
  path->points.clear();
  for (const PathFrame& f : frames) path->points.push_back(f.point);
  path->length_mm = 0.0;
  path->max_step_mm = 0.0;
  path->min_step_mm = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < path->points.size(); ++k) {
    const double step = (path->points[(k + 1) % path->points.size()] - path->points[k]).norm();
    path->length_mm += step;
    path->max_step_mm = std::max(path->max_step_mm, step);
    path->min_step_mm = std::min(path->min_step_mm, step);
  }
}

// Welds, poses and intersects; the main loop of the intersection (islands dropped) or the failed check.
MainCurve intersect_and_select(const Mesh& leg_L, const Mesh& stub_S, const Eigen::Isometry3d& T_S_L,
                               const TubeJointSolveOptions& options, TubeJointSolution* solution, Mesh* leg_S,
                               Mesh* stub) {
  solution->leg_weld_tolerance_mm = options.weld_edge_fraction * median_edge_length(leg_L);
  solution->stub_weld_tolerance_mm = options.weld_edge_fraction * median_edge_length(stub_S);
  MeshWeldResult leg = weld_near_vertices(leg_L, solution->leg_weld_tolerance_mm, "leg mesh");
  MeshWeldResult welded_stub = weld_near_vertices(stub_S, solution->stub_weld_tolerance_mm, "stub mesh");
  solution->leg_welded_vertices = leg.merged_vertices;
  solution->stub_welded_vertices = welded_stub.merged_vertices;
  const MeshWeldResult* welded[2] = {&leg, &welded_stub};
  const double tolerance[2] = {solution->leg_weld_tolerance_mm, solution->stub_weld_tolerance_mm};
  for (int k = 0; k < 2; ++k) {
    if (welded[k]->merged_vertices == 0) continue;
    solution->warnings.push_back(std::string(k == 0 ? "leg" : "stub") +
                                 " mesh: " + std::to_string(welded[k]->merged_vertices) +
                                 " vertices welded into others within " + format_fixed(tolerance[k], 4) + " mm (" +
                                 format_fixed(100.0 * options.weld_edge_fraction, 1) + " % of the median edge; " +
                                 std::to_string(welded[k]->dropped_faces) + " faces collapsed)");
  }
  *leg_S = posed(leg.mesh, T_S_L);
  *stub = std::move(welded_stub.mesh);
  const MeshIntersectionResult cut = intersect_meshes(*leg_S, *stub, options.intersection);
  solution->segments = cut.segments.size();
  solution->candidate_pairs = cut.candidate_pairs;
  const IntersectionGraph graph = weld_segments(cut.segments);
  solution->curve_vertices = graph.vertices.size();
  MainCurve main = select_main_curve(graph, options.max_island_ratio);
  solution->islands = main.islands;
  solution->longest_island_mm = main.longest_island_mm;
  if (main.islands > 0) {
    std::ostringstream text;
    text.precision(4);
    text << "dropped " << main.islands << " intersection island(s) of " << main.island_vertices
         << " vertices (the longest " << main.longest_island_mm << " mm, the curve " << main.main_length_mm
         << " mm): the surfaces nearly touch there, within the scanner noise";
    solution->warnings.push_back(text.str());
  }
  return main;
}

// Noise, edges and curvature of both scans near the seam; the facet error bound ([coarse] when above the limit) and
// the backtrack tolerance (automatic unless given) they imply.
CurveCheck measure_scans(const Mesh& leg_S, const Mesh& stub, const IntersectionGraph& curve,
                         const TubeJointSolveOptions& options, TubeJointSolution* solution) {
  const int k_quality = std::min<int>(40, static_cast<int>(std::min(leg_S.vertices.size(), stub.vertices.size())));
  if (k_quality >= 6) {
    solution->leg_quality = estimate_scan_quality(leg_S, curve.vertices, k_quality, 96);
    solution->stub_quality = estimate_scan_quality(stub, curve.vertices, k_quality, 96);
  }
  const ScanQuality& leg = solution->leg_quality;
  const ScanQuality& stb = solution->stub_quality;
  const double sin_beta = std::max(0.05, min_crossing_sine(leg, stb));
  solution->min_crossing_deg = std::asin(std::min(1.0, sin_beta)) * 180.0 / 3.141592653589793;
  warn_coarse("leg", leg, &solution->warnings);
  warn_coarse("stub", stb, &solution->warnings);
  const auto sagitta = [](const ScanQuality& q) { return q.edge_mm * q.edge_mm * q.curvature_per_mm / 8.0; };
  solution->facet_error_mm = (sagitta(leg) + sagitta(stb)) / sin_beta;
  solution->backtrack_tolerance_mm =
      options.backtrack_tolerance_mm >= 0.0
          ? options.backtrack_tolerance_mm
          : std::max(0.05, TubeJointSolveOptions::kBacktrackEdges * std::max(leg.edge_mm, stb.edge_mm) +
                               TubeJointSolveOptions::kBacktrackSigmas * std::max(leg.noise_mm, stb.noise_mm) / sin_beta);
  if (solution->facet_error_mm <= options.max_facet_error_mm) return {};
  std::ostringstream what;
  what.precision(3);
  what << "the meshes are too coarse for their curvature: their facets alone can put the seam "
       << solution->facet_error_mm << " mm off (edges leg " << leg.edge_mm << " mm, stub " << stb.edge_mm
       << " mm; the surfaces cross at " << solution->min_crossing_deg << " deg at least; limit "
       << options.max_facet_error_mm << " mm): remesh finer";
  return curve_failure("coarse", what.str(), curve.vertices.front());
}

}  // namespace

TubeJointSolution solve_tube_joint(const Mesh& leg_L, const Mesh& stub_S, const Eigen::Isometry3d& T_S_L,
                                   const TubeJointSolveOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube-joint: " + why);
  const auto start = std::chrono::steady_clock::now();
  TubeJointSolution solution;
  report(options.progress, "intersect", 0.0);
  Mesh leg_S;
  Mesh stub;
  const MainCurve main = intersect_and_select(leg_L, stub_S, T_S_L, options, &solution, &leg_S, &stub);
  solution.intersection_seconds = seconds_since(start);
  report(options.progress, "intersect", 1.0);
  if (!main.check.ok) return failed(solution, main.check);
  report(options.progress, "path", 0.0);
  const CurveCheck fine = measure_scans(leg_S, stub, main.graph, options, &solution);
  if (!fine.ok) return failed(solution, fine);
  AzimuthOrderOptions order_options;
  order_options.backtrack_tolerance_mm = solution.backtrack_tolerance_mm;
  const double n = static_cast<double>(main.graph.vertices.size());
  order_options.smoothing_mm2 = options.sampling.smoothing_rms_mm > 0.0
                                    ? n * options.sampling.smoothing_rms_mm * options.sampling.smoothing_rms_mm
                                    : options.sampling.smoothing_mm2;
  const AzimuthOrder order = order_by_azimuth(main.graph, order_options);
  solution.dropped_vertices = order.dropped;
  solution.merged_vertices = order.merged;
  solution.max_backtrack_mm = order.max_backtrack_mm;
  if (!order.check.ok) return failed(solution, order.check);
  PathSamplingOptions sampling = options.sampling;  // smoothed above, before the azimuth test
  sampling.smoothing_mm2 = -1.0;
  sampling.smoothing_rms_mm = 0.0;
  solution.path = sample_path(order, sampling);
  solution.path.smoothed = order.smoothed;
  solution.path.smoothing_rms_mm = order.smoothing_rms_mm;
  if (!solution.path.check.ok) return failed(solution, solution.path.check);
  report(options.progress, "normals", 0.0);
  TubeAxis stub_axis;  // z_S through the origin
  TubeAxis leg_axis;
  leg_axis.point = T_S_L.translation();
  leg_axis.direction = T_S_L.linear().col(2);
  solution.frames = joint_geometry(solution.path.phi_rad, solution.path.points, stub, stub_axis, leg_S, leg_axis,
                                   options.geometry, &solution.refined_points);
  measure_written_path(solution.frames, &solution.path);
  if (options.geometry.k_refine != 0 && solution.refined_points < solution.frames.size()) {
    solution.warnings.push_back("refined " + std::to_string(solution.refined_points) + " of " +
                                std::to_string(solution.frames.size()) +
                                " path points onto the local surface fits; the others keep the intersection "
                                "polyline's point (the fits did not meet within the largest move)");
  }
  // How well the scans determine the directions: 2 sigma of the tangent (Eq. 3 from the fitted normals; the cut and
  // weld directions and the dihedral angle follow from it and the normals).
  const PathFrame* worst = nullptr;
  for (const PathFrame& f : solution.frames) {
    if (worst == nullptr || f.tangent_sigma_deg > worst->tangent_sigma_deg) worst = &f;
    solution.normal_sigma_deg_max =
        std::max({solution.normal_sigma_deg_max, f.stub_normal_sigma_deg, f.leg_normal_sigma_deg});
  }
  if (worst != nullptr) solution.tangent_sigma_deg_max = worst->tangent_sigma_deg;
  solution.tools = tool_paths(solution.frames, options.tools);
  if (worst != nullptr && 2.0 * worst->tangent_sigma_deg > options.max_direction_error_deg) {
    std::ostringstream what;
    what.precision(3);
    what << "the seam tangent is not determined within " << options.max_direction_error_deg << " deg at azimuth "
         << worst->phi_rad * 180.0 / kPi << " deg: the surfaces cross at "
         << std::asin(std::min(1.0, worst->stub_normal.cross(worst->leg_normal).norm())) * 180.0 / kPi
         << " deg there and the scans' noise leaves +-" << 2.0 * worst->tangent_sigma_deg
         << " deg (2 sigma from the local surface fits' normals, " << worst->stub_normal_sigma_deg << " and "
         << worst->leg_normal_sigma_deg << " deg): scan with less noise or raise --max-direction-error";
    solution.total_seconds = seconds_since(start);
    return failed(solution, curve_failure("directions", what.str(), worst->point));
  }
  solution.safety = check_tool_safety(solution.frames, solution.tools, leg_axis, options.tools, options.safety);
  report(options.progress, "normals", 1.0);
  solution.total_seconds = seconds_since(start);
  if (!solution.safety.ok) {
    CurveCheck unsafe;
    unsafe.ok = false;
    unsafe.condition = "safety";
    unsafe.message = "[safety] " + solution.safety.message;
    return failed(solution, unsafe);
  }
  solution.ok = true;
  solution.termination = "closed curve";
  return solution;
}

bool TubeJointJobOptions::IsValid(std::string* error) const {
  std::string why;
  if (leg_path.empty() || stub_path.empty()) {
    why = "give both meshes: the leg (outer surface, leg frame) and the stub (inner surface, stub frame)";
  } else if (leg_pose_path.empty() && !spec.IsValid(&why)) {
    why = "joint: " + why;
  } else if (leg_pose_path.empty() && !(spec.protrusion_mm > 0.0)) {
    why = "joint: the protrusion (the stub's distal end to the leg axis, along the stub axis) must be > 0 mm";
  } else if (!(std::isfinite(marker_tolerance_mm) && marker_tolerance_mm > 0.0)) {
    why = "the marker tolerance must be > 0 mm";
  } else if (!solve.IsValid(&why)) {
  } else {
    for (const std::string* path : {&out_path, &out_cut, &out_weld}) {
      if (!path->empty() && file_extension(*path) != ".csv") why = *path + ": outputs are written as .csv";
    }
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

namespace {

double median_radius(const Mesh& mesh, const Eigen::Isometry3d& T_axis_mesh) {
  std::vector<double> radii;
  const std::size_t stride = std::max<std::size_t>(1, mesh.vertices.size() / 20000);
  for (std::size_t i = 0; i < mesh.vertices.size(); i += stride) radii.push_back((T_axis_mesh * mesh.vertices[i]).head<2>().norm());
  const auto middle = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
  std::nth_element(radii.begin(), middle, radii.end());
  return *middle;
}

// Meshes in metres (or a spec in metres) are bad input, not geometry: say so before intersecting.
void check_units(const TubeJointJobOptions& options, const Mesh& leg_L, const Mesh& stub_S, TubeJointJobResult* r) {
  r->stub_radius_mm = median_radius(stub_S, Eigen::Isometry3d::Identity());
  r->leg_radius_mm = median_radius(leg_L, Eigen::Isometry3d::Identity());
  std::ostringstream why;
  why.precision(4);
  if (!(r->stub_radius_mm > 0.0 && r->leg_radius_mm > 0.0)) {
    why << "the meshes lie on their tubes' axes (radius 0): are they in their frames (L and S)?";
  } else if (r->leg_radius_mm > 1000.0 * r->stub_radius_mm || r->stub_radius_mm > 1000.0 * r->leg_radius_mm) {
    why << "the leg's radius " << r->leg_radius_mm << " and the stub's " << r->stub_radius_mm
        << " differ by more than 1000x: are the two meshes in the same unit (mm)?";
  } else if (options.leg_pose_path.empty()) {
    const double protrusion = options.spec.protrusion_mm;
    if (protrusion > 100.0 * r->leg_radius_mm) {
      why << "the meshes are far smaller than the joint: leg radius " << r->leg_radius_mm << ", stub radius "
          << r->stub_radius_mm << " against a protrusion of " << protrusion
          << " mm; are they in metres? Convert them to mm";
    } else if (protrusion < 0.01 * r->leg_radius_mm) {
      why << "the joint is far smaller than the meshes: a protrusion of " << protrusion << " mm against a leg radius of "
          << r->leg_radius_mm << " mm; give --protrusion in mm";
    }
  }
  if (why.tellp() > 0) throw Error(options.leg_path + ", " + options.stub_path + ": " + why.str());
}

}  // namespace

TubeJointJobResult run_tube_joint(const TubeJointJobOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube-joint: " + why);
  TubeJointJobResult result;
  result.T_S_L = options.leg_pose_path.empty() ? T_L_S(options.spec).inverse() : read_transform(options.leg_pose_path);
  if (!options.cad.save_mesh_path.empty() && is_cad_file(options.leg_path) && is_cad_file(options.stub_path)) {
    throw Error(options.cad.save_mesh_path + ": --cad-save-mesh takes one CAD file's tessellation, and the leg and the "
                "stub are both CAD; save each with `conform info FILE --cad-save-mesh MESH`");
  }
  const ReadOptions read = detail::read_options(NonFinitePolicy::kReject, options.cad);
  ReadReport leg_report, stub_report;
  Mesh leg = read_mesh(options.leg_path, read, &leg_report);
  Mesh stub = read_mesh(options.stub_path, read, &stub_report);
  detail::keep_cad_report(leg_report, result.cad_inputs);
  detail::keep_cad_report(stub_report, result.cad_inputs);
  if (leg_report.cad.read) leg = with_surface_points(std::move(leg));
  if (stub_report.cad.read) stub = with_surface_points(std::move(stub));
  if (!leg.has_faces()) throw Error(options.leg_path + ": the leg must be a triangle mesh (it has no faces)");
  if (!stub.has_faces()) throw Error(options.stub_path + ": the stub must be a triangle mesh (it has no faces)");
  if (!options.leg_markers_path.empty()) {
    result.leg_reference = tube_frame_from_marker_file(leg, options.leg_markers_path, options.marker_tolerance_mm);
    result.leg_marker_residuals_mm = result.leg_reference.marker_residuals_mm;
    leg = posed(leg, result.leg_reference.T_tube_scan);
  }
  if (!options.stub_markers_path.empty()) {
    result.stub_reference = tube_frame_from_marker_file(stub, options.stub_markers_path, options.marker_tolerance_mm);
    result.stub_marker_residuals_mm = result.stub_reference.marker_residuals_mm;
    stub = posed(stub, result.stub_reference.T_tube_scan);
  }
  check_units(options, leg, stub, &result);
  result.leg_faces = leg.faces.size();
  result.stub_faces = stub.faces.size();
  if (options.keep_geometry) result.leg_L = leg, result.stub_S = stub;
  result.solution = solve_tube_joint(leg, stub, result.T_S_L, options.solve);
  if (!result.solution.ok) return result;
  const ToolPaths& tools = result.solution.tools;
  const std::vector<double> weld_alpha(tools.weld.size(), tools.weld_angle_rad);
  write_all({{options.out_path, tube_joint_path_csv(result.solution.frames)},
             {options.out_cut, tube_joint_tool_csv(tools.cut, tools.groove_rad, tools.psi_rad)},
             {options.out_weld, tube_joint_tool_csv(tools.weld, weld_alpha, tools.psi_rad)}},
            &result.written);
  return result;
}

TubeReferenceResult tube_frame_from_marker_file(const Mesh& mesh, const std::string& markers_path,
                                                double tolerance_mm) {
  const CsvTable table = read_csv(markers_path, {"x_mm", "y_mm", "z_mm", "ref_x_mm", "ref_y_mm", "ref_z_mm"});
  const Eigen::MatrixXd scan = table.numbers({"x_mm", "y_mm", "z_mm"});
  const Eigen::MatrixXd known = table.numbers({"ref_x_mm", "ref_y_mm", "ref_z_mm"});
  if (table.rows() < 3) throw Error(markers_path + ": " + std::to_string(table.rows()) + " markers; give at least 3");
  std::vector<Eigen::Vector3d> markers_scan;
  std::vector<Eigen::Vector3d> markers_tube;
  for (Eigen::Index i = 0; i < scan.rows(); ++i) {
    markers_scan.emplace_back(scan.row(i).transpose());
    markers_tube.emplace_back(known.row(i).transpose());
  }
  TubeReferenceOptions options;
  options.max_marker_residual_mm = tolerance_mm;
  TubeReferenceResult reference =
      tube_reference(mesh.vertices, vertex_normals_from_faces(mesh), markers_scan, markers_tube, options);
  if (!reference.ok) throw Error(markers_path + ": " + reference.termination);
  return reference;
}

std::string tube_joint_path_csv(const std::vector<PathFrame>& frames) {
  CsvWriter csv({"phi_rad", "x_mm", "y_mm", "z_mm", "tx", "ty", "tz", "nsx", "nsy", "nsz", "nlx", "nly", "nlz"}, 9);
  for (const PathFrame& f : frames) {
    csv.cell(f.phi_rad);
    for (const Eigen::Vector3d* v : {&f.point, &f.tangent, &f.stub_normal, &f.leg_normal}) {
      csv.cell(v->x()).cell(v->y()).cell(v->z());
    }
    csv.end_row();
  }
  return csv.text();
}

std::string tube_joint_tool_csv(const std::vector<ToolPose>& poses, const std::vector<double>& alpha_rad,
                                const std::vector<double>& psi_rad) {
  if (alpha_rad.size() != poses.size() || psi_rad.size() != poses.size()) {
    throw Error("tube-joint: tool CSV: one alpha and one psi per pose");
  }
  CsvWriter csv({"phi_rad", "x_mm", "y_mm", "z_mm", "dx", "dy", "dz", "alpha_rad", "psi_rad"}, 9);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const ToolPose& p = poses[i];
    csv.cell(p.phi_rad).cell(p.position.x()).cell(p.position.y()).cell(p.position.z());
    csv.cell(p.direction.x()).cell(p.direction.y()).cell(p.direction.z());
    csv.cell(alpha_rad[i]).cell(psi_rad[i]);
    csv.end_row();
  }
  return csv.text();
}

}  // namespace conform
