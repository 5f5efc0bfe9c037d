#include "conform/pipelines/fit_cylinder/fit_cylinder.h"

#include <cstdio>
#include <string>
#include <vector>

#include "conform/core/atomic_file.h"
#include "conform/core/error.h"
#include "conform/core/io.h"
#include "conform/core/mesh_sampling.h"
#include "conform/core/normals.h"
#include "conform/core/phong_surface.h"
#include "common/cad_inputs.h"

namespace conform {
namespace {

std::vector<Eigen::Vector3d> normals_for(const Mesh& mesh, const FitCylinderJobOptions& options, NormalSource* source) {
  if (mesh.has_normals()) {
    *source = NormalSource::kFile;
    return mesh.normals;
  }
  report(options.fit.progress, "cylinder: normals", 0.0);
  std::vector<Eigen::Vector3d> normals;
  if (mesh.has_faces()) {
    *source = NormalSource::kMeshPca;
    normals = estimate_normals(mesh, options.fit.normal_neighbors);
  } else {
    *source = NormalSource::kCloudPca;
    NormalOptions pca;
    pca.k = options.fit.normal_neighbors;
    for (const auto& n : estimate_normals(to_cloud(mesh), pca))
      normals.emplace_back(n.normal_x, n.normal_y, n.normal_z);
  }
  report(options.fit.progress, "cylinder: normals", 1.0);
  return normals;
}

// The points to fit and their normals: the vertices, or samples of the smooth surface of a mesh.
std::vector<Eigen::Vector3d> points_for(const Mesh& mesh, const FitCylinderJobOptions& options, bool cad,
                                        FitCylinderJobResult& result, std::vector<Eigen::Vector3d>& normals) {
  const bool surface = options.points == CylinderPoints::kSurface || (options.points == CylinderPoints::kAuto && cad);
  if (!surface) {
    normals = normals_for(mesh, options, &result.normals);
    return mesh.vertices;
  }
  if (!mesh.has_faces()) {
    throw Error("--points surface needs a mesh with faces; this input is a point cloud (use --points vertices)");
  }
  report(options.fit.progress, "cylinder: surface samples", 0.0);
  const PhongSurface smooth(mesh, mesh.has_normals() ? mesh.normals : std::vector<Eigen::Vector3d>{});
  MeshSurfaceSample sample = sample_mesh_surface(mesh, options.surface_samples, &smooth);
  report(options.fit.progress, "cylinder: surface samples", 1.0);
  result.surface_points = true;
  result.normals = NormalSource::kSurface;
  normals = std::move(sample.normals);
  return std::move(sample.points);
}

}  // namespace

const char* to_string(CylinderPoints points) {
  switch (points) {
    case CylinderPoints::kAuto:
      return "auto";
    case CylinderPoints::kVertices:
      return "vertices";
    case CylinderPoints::kSurface:
      return "surface";
  }
  return "unknown";
}

const char* to_string(NormalSource source) {
  switch (source) {
    case NormalSource::kFile:
      return "file";
    case NormalSource::kMeshPca:
      return "pca (mesh faces)";
    case NormalSource::kCloudPca:
      return "pca";
    case NormalSource::kSurface:
      return "surface";
  }
  return "unknown";
}

bool FitCylinderJobOptions::IsValid(std::string* error) const {
  const auto fail = [error](const std::string& why) {
    if (error != nullptr) *error = why;
    return false;
  };
  if (input_path.empty()) return fail("no input file given");
  if (!out_path.empty() && file_extension(out_path) != ".csv") {
    return fail(out_path + ": the residuals file must be .csv");
  }
  if (surface_samples == 0) return fail("the number of surface samples must be > 0");
  std::string why;
  if (!fit.IsValid(&why)) return fail(why);
  return true;
}

std::string cylinder_residuals_csv(const std::vector<Eigen::Vector3d>& points, const CylinderFitResult& fit) {
  std::string csv = "i,x_mm,y_mm,z_mm,distance_mm,inlier\n";
  csv.reserve(csv.size() + points.size() * 64);
  std::size_t next_inlier = 0;
  char row[160];
  for (std::size_t i = 0; i < points.size(); ++i) {
    const bool inlier = next_inlier < fit.inliers.size() && static_cast<std::size_t>(fit.inliers[next_inlier]) == i;
    next_inlier += inlier ? 1 : 0;
    const Eigen::Vector3d& p = points[i];
    std::snprintf(row, sizeof(row), "%zu,%.6f,%.6f,%.6f,%.6f,%d\n", i, p.x(), p.y(), p.z(),
                  signed_distance(fit.cylinder, p), inlier ? 1 : 0);
    csv += row;
  }
  return csv;
}

FitCylinderJobResult run_fit_cylinder(const FitCylinderJobOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("fit-cylinder: " + why);
  ReadReport report;
  const ReadOptions read = detail::read_options(NonFinitePolicy::kReject, options.cad);  // NaN: an error
  const Mesh mesh = read_geometry(options.input_path, read, &report);
  FitCylinderJobResult result;
  result.input_path = options.input_path;
  result.input_faces = mesh.faces.size();
  result.warnings = report.warnings;
  detail::keep_cad_report(report, result.cad_inputs);
  std::vector<Eigen::Vector3d> points;
  try {
    std::vector<Eigen::Vector3d> normals;
    points = points_for(mesh, options, report.cad.read, result, normals);
    result.points = points.size();
    result.fit = fit_cylinder(points, normals, options.fit);
  } catch (const Error& e) {
    throw Error(options.input_path + ": " + e.what());
  }
  if (result.normals == NormalSource::kCloudPca) result.fit.side = CylinderSide::kUnknown;
  for (const std::string& w : result.fit.warnings) {
    result.warnings.push_back("fit-cylinder: " + options.input_path + ": " + w);
  }
  if (!options.out_path.empty()) {
    write_file_atomically(options.out_path, cylinder_residuals_csv(points, result.fit));
    result.out_path = options.out_path;
  }
  if (options.keep_geometry) result.points_mm = mesh.vertices;
  return result;
}

}  // namespace conform
