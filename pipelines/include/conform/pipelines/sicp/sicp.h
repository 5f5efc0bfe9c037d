#pragma once
// `conform sicp`: deburring on a deformed part. Reads the nominal contour (CSV x_mm,y_mm,z_mm in order, or a mesh
// whose boundary is taken), the scan of the deformed part, the nominal trajectory (CSV x_mm,y_mm,z_mm,nx,ny,nz) and
// optionally the nominal surface around the contour; registers (registration/sicp.h) and maps the trajectory onto
// the part by one of three models: Subdivision-ICP (blended segment transforms), one rigid transform, or the rigid
// transform plus a smooth height field (the paper's projection model); re-estimates the tool normals from the scan.
// Writes the compensated trajectory (same rows, same order) only when the registration converged and the path passed
// its checks (compensation/sicp_checks.h), whole or not at all. Given the ground-truth trajectory (generated data), it reports the error.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "conform/compensation/projection_model.h"
#include "conform/compensation/sicp_checks.h"
#include "conform/compensation/sicp_surface_misfit.h"
#include "conform/compensation/trajectory.h"
#include "conform/compensation/trajectory_error.h"
#include "conform/core/cad.h"
#include "conform/core/mesh.h"
#include "conform/core/polyline.h"
#include "conform/core/progress.h"
#include "conform/registration/sicp.h"

namespace conform {

enum class SicpModel { kSicp, kRigid, kProjection };
const char* to_string(SicpModel model);

// The part of the job that works on data in memory (what the tests and the benchmark call).
struct SicpCompensationOptions {
  SicpModel model = SicpModel::kSicp;
  SicpOptions sicp;  // its scan_voxel_mm thins the scan once, for the registration and the tool normals
  ProjectionOptions projection;
  ToolNormalOptions normals;
  SicpCheckOptions checks;
  SicpMisfitOptions misfit;  // the fit of the scan's residuals at each row that checks.max_surface_offset_mm judges
};

struct SicpCompensationResult {
  SicpModel model = SicpModel::kSicp;
  SicpResult registration;     // coarse ICP always; segments for kSicp
  ProjectionModel projection;  // kProjection
  Trajectory trajectory;       // compensated, same rows as the nominal one
  std::size_t normals_from_scan = 0;
  SicpCheck check;         // noise, blind and outlier segments, per-row split and confidence
  bool converged = false;  // the registration converged
  bool trusted = false;    // converged, and every row passed the checks (check.reason says why not)
  std::string termination;
};

// surface: the nominal surface around the contour; nullptr (contour-only, the paper's variant) is refused with a
// conform::Error: without edge points found in the scan (the paper's section 2.1, not done here) the contour's points
// pair with the surface beside the edge and the path comes out worse than rigid. scan: the deformed part.
SicpCompensationResult compensate_trajectory(const Polyline& contour, const Mesh* surface,
                                             const std::vector<Eigen::Vector3d>& scan, const Trajectory& nominal,
                                             const SicpCompensationOptions& options);

struct SicpJobOptions {
  std::string contour_path;         // .csv (x_mm,y_mm,z_mm, ordered) or a mesh (.ply .stl .obj) whose boundary is taken
  std::string scan_path;            // cloud or mesh
  std::string trajectory_path;      // .csv x_mm,y_mm,z_mm,nx,ny,nz
  std::string surface_path;         // optional nominal surface mesh or CAD; a mesh contour is its own surface
  CadReadOptions cad;               // a CAD surface: its tessellation (core/cad.h)
  std::string truth_path;           // optional ground-truth trajectory, same columns and rows: errors reported
  std::string out_trajectory_path;  // optional
  std::string out_rows_path;        // optional: per-row correction split and confidence (CSV), written with the above
  SicpCompensationOptions compensation;
  ProgressFn progress;  // "read", the registration's stages, "normals", "write"
  bool keep_geometry = false;  // keep the contour, the scan and the nominal trajectory in the result (for a report)
  bool IsValid(std::string* error) const;
};

struct SicpJobResult {
  SicpCompensationResult compensation;
  std::string contour_source;  // "csv (closed)", "mesh boundary 2 of 3 (closed)"
  std::size_t contour_points = 0;
  double contour_length_mm = 0.0;
  std::size_t scan_points = 0;
  std::size_t trajectory_rows = 0;
  std::size_t surface_faces = 0;
  std::optional<TrajectoryError> error;  // when a truth was given
  std::vector<std::string> warnings;
  std::vector<CadReport> cad_inputs;  // the surface, when it was CAD
  std::string out_trajectory_path;  // written; empty when not
  std::string out_rows_path;        // written; empty when not
  // With keep_geometry (else empty): what was read, for a report (pipelines/sicp/sicp_report.h).
  Polyline contour;
  std::vector<Eigen::Vector3d> scan;
  Trajectory nominal;
};

// Throws conform::Error for bad input (files, columns, rows, a contour mesh without boundary); not converging is
// reported in the result (compensation.converged), with no file written.
SicpJobResult run_sicp(const SicpJobOptions& options);

}  // namespace conform
