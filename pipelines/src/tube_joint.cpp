#include "conform/pipelines/tube_joint.h"

#include <chrono>
#include <cstdio>

#include "conform/core/atomic_file.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/output_set.h"
#include "conform/core/transform_io.h"
#include "conform/registration/tube_reference.h"
#include "conform/toolpath/intersection_graph.h"

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
  if (!intersection.IsValid(&why) || !sampling.IsValid(&why) || !geometry.IsValid(&why) || !tools.IsValid(&why)) {
  } else if (!(backtrack_tolerance_mm >= 0.0)) {
    why = "backtrack tolerance must be >= 0 mm";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

TubeJointSolution solve_tube_joint(const Mesh& leg_L, const Mesh& stub_S, const Eigen::Isometry3d& T_S_L,
                                   const TubeJointSolveOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube-joint: " + why);
  const auto start = std::chrono::steady_clock::now();
  TubeJointSolution solution;
  report(options.progress, "intersect", 0.0);
  const Mesh leg_S = posed(leg_L, T_S_L);
  const MeshIntersectionResult cut = intersect_meshes(leg_S, stub_S, options.intersection);
  solution.segments = cut.segments.size();
  solution.candidate_pairs = cut.candidate_pairs;
  const IntersectionGraph graph = weld_segments(cut.segments);
  solution.curve_vertices = graph.vertices.size();
  solution.intersection_seconds = seconds_since(start);
  report(options.progress, "intersect", 1.0);
  const CurveCheck check = check_intersection_graph(graph);
  if (!check.ok) return failed(solution, check);
  report(options.progress, "path", 0.0);
  const AzimuthOrder order = order_by_azimuth(graph, options.backtrack_tolerance_mm);
  solution.dropped_vertices = order.dropped;
  if (!order.check.ok) return failed(solution, order.check);
  solution.path = sample_path(order, options.sampling);
  if (!solution.path.check.ok) return failed(solution, solution.path.check);
  report(options.progress, "normals", 0.0);
  TubeAxis stub_axis;  // z_S through the origin
  TubeAxis leg_axis;
  leg_axis.point = T_S_L.translation();
  leg_axis.direction = T_S_L.linear().col(2);
  solution.frames =
      joint_geometry(solution.path.phi_rad, solution.path.points, stub_S, stub_axis, leg_S, leg_axis, options.geometry);
  solution.tools = tool_paths(solution.frames, options.tools);
  report(options.progress, "normals", 1.0);
  solution.ok = true;
  solution.termination = "closed curve";
  solution.total_seconds = seconds_since(start);
  return solution;
}

bool TubeJointJobOptions::IsValid(std::string* error) const {
  std::string why;
  if (leg_path.empty() || stub_path.empty()) {
    why = "give both meshes: the leg (outer surface, leg frame) and the stub (inner surface, stub frame)";
  } else if (leg_pose_path.empty() && !spec.IsValid(&why)) {
    why = "joint: " + why;
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

TubeJointJobResult run_tube_joint(const TubeJointJobOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube-joint: " + why);
  TubeJointJobResult result;
  result.T_S_L = options.leg_pose_path.empty() ? T_L_S(options.spec).inverse() : read_transform(options.leg_pose_path);
  Mesh leg = read_mesh(options.leg_path);
  Mesh stub = read_mesh(options.stub_path);
  if (!leg.has_faces()) throw Error(options.leg_path + ": the leg must be a triangle mesh (it has no faces)");
  if (!stub.has_faces()) throw Error(options.stub_path + ": the stub must be a triangle mesh (it has no faces)");
  if (!options.leg_markers_path.empty()) {
    leg = posed(leg, tube_frame_from_marker_file(leg, options.leg_markers_path, &result.leg_marker_residuals_mm));
  }
  if (!options.stub_markers_path.empty()) {
    stub = posed(stub, tube_frame_from_marker_file(stub, options.stub_markers_path, &result.stub_marker_residuals_mm));
  }
  result.leg_faces = leg.faces.size();
  result.stub_faces = stub.faces.size();
  result.solution = solve_tube_joint(leg, stub, result.T_S_L, options.solve);
  if (!result.solution.ok) return result;
  write_all({{options.out_path, tube_joint_path_csv(result.solution.frames)},
             {options.out_cut, tube_joint_tool_csv(result.solution.tools.cut)},
             {options.out_weld, tube_joint_tool_csv(result.solution.tools.weld)}},
            &result.written);
  return result;
}

Eigen::Isometry3d tube_frame_from_marker_file(const Mesh& mesh, const std::string& markers_path,
                                              std::vector<double>* residuals_mm) {
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
  const TubeReferenceResult reference =
      tube_reference(mesh.vertices, vertex_normals_from_faces(mesh), markers_scan, markers_tube);
  if (!reference.ok) throw Error(markers_path + ": " + reference.termination);
  *residuals_mm = reference.marker_residuals_mm;
  return reference.T_tube_scan;
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

std::string tube_joint_tool_csv(const std::vector<ToolPose>& poses) {
  CsvWriter csv({"phi_rad", "x_mm", "y_mm", "z_mm", "dx", "dy", "dz"}, 9);
  for (const ToolPose& p : poses) {
    csv.cell(p.phi_rad).cell(p.position.x()).cell(p.position.y()).cell(p.position.z());
    csv.cell(p.direction.x()).cell(p.direction.y()).cell(p.direction.z());
    csv.end_row();
  }
  return csv.text();
}

}  // namespace conform
