#pragma once
// `conform fit-cylinder`: the axis, radius and inliers of a scanned tube (fitting/cylinder.h), read from any cloud or
// mesh file, with an optional CSV of every point's distance to the fitted surface.
//
// Normals: the file's own when it has them; PCA normals oriented by the faces for a mesh; PCA normals (orientation
// unknown) for a bare cloud.

#include <cstddef>
#include <string>
#include <vector>

#include "conform/core/cad.h"
#include "conform/fitting/cylinder.h"

namespace conform {

// Which points are fitted.
enum class CylinderPoints {
  kAuto,      // a CAD input's surface samples, every other input's vertices (a scanner's mesh: its measurements)
  kVertices,  // the file's points
  kSurface,   // points spread over a mesh's smooth surface (sample_mesh_surface): a coarse or CAD-like mesh, whose
              // vertices may lie on its faces' rims only
};
const char* to_string(CylinderPoints points);  // "auto", "vertices", "surface"

struct FitCylinderJobOptions {
  std::string input_path;  // .ply .stl .obj .pcd .xyz .txt .asc .csv; CAD .step .stp .iges .igs
  CadReadOptions cad;      // a CAD input: its tessellation (core/cad.h)
  CylinderFitOptions fit;  // threshold, radius bounds, axis prior, seed, normal_neighbors, progress ...
  CylinderPoints points = CylinderPoints::kAuto;
  // Surface samples (kSurface): this many, by area, on the smooth surface (core/phong_surface.h) with its normals.
  std::size_t surface_samples = 20000;
  std::string out_path;    // CSV to write, whole or not at all; empty: none
  bool keep_geometry = false;  // keep the points in the result, for a report

  // False (and why) when the input path is empty, the output is not .csv, surface_samples is 0, or the fit options
  // are not valid.
  bool IsValid(std::string* error) const;
};

enum class NormalSource { kFile, kMeshPca, kCloudPca, kSurface };
const char* to_string(NormalSource source);  // "file", "pca (mesh faces)", "pca", "surface"

struct FitCylinderJobResult {
  CylinderFitResult fit;
  std::string input_path;
  std::size_t points = 0;                     // fitted: the file's, or the surface samples
  bool surface_points = false;                // the points are samples of the mesh's surface, not its vertices
  std::size_t input_faces = 0;                // the input mesh's faces (0: a cloud)
  NormalSource normals = NormalSource::kFile;
  std::vector<std::string> warnings;  // what the reader noticed, then what the fit found doubtful (fit.warnings)
  std::vector<CadReport> cad_inputs;  // the input, when it was CAD
  std::string out_path;               // the CSV written; empty when none was asked for
  std::vector<Eigen::Vector3d> points_mm;  // with options.keep_geometry: the input's points (else empty)
};

// Throws conform::Error naming the file (unreadable, malformed, NaN coordinates, too few points, all points on a
// line, surface points asked of a cloud) or the bad option. A plane, a sphere or too few inliers is a result with fit.ok false (and the CSV is still
// written when asked for, so that the failure can be inspected).
FitCylinderJobResult run_fit_cylinder(const FitCylinderJobOptions& options);

// The CSV: header `i,x_mm,y_mm,z_mm,distance_mm,inlier`, one row per fitted point (file order, or sample order), distance signed
// (positive away from the axis), 6 decimals; inlier 1 or 0.
std::string cylinder_residuals_csv(const std::vector<Eigen::Vector3d>& points, const CylinderFitResult& fit);

}  // namespace conform
