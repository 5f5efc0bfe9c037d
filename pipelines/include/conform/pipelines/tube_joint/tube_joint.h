#pragma once
// `conform tube-joint`: cutting and welding paths for a tubular joint from a scan of the leg's outer surface and of
// the stub's inner surface (Lind & Ystgaard 2020). Steps: pose the leg mesh in the stub frame S -> intersect the
// meshes -> weld and check the intersection graph (conditions (1a)-(1i), toolpath/intersection/intersection_graph.h) -> order by
// stub azimuth -> smooth and resample -> PCA normals, tangent -> cutting and welding poses -> CSV files.
//
// A curve that fails a condition (no intersection, two curves, an open or branching curve, not parameterisable by
// azimuth) is a result with ok == false and a message naming the condition and where: the job ran, the meshes were
// readable, but the joint they describe has no single closed seam (CLI exit 1). No file is written then.

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/cad.h"
#include "conform/core/mesh.h"
#include "conform/core/progress.h"
#include "conform/registration/tube_reference.h"
#include "conform/toolpath/intersection/azimuth_path.h"
#include "conform/toolpath/intersection/joint_frames.h"
#include "conform/toolpath/intersection/joint_geometry.h"
#include "conform/toolpath/intersection/mesh_intersection.h"
#include "conform/toolpath/intersection/scan_quality.h"
#include "conform/toolpath/intersection/tool_paths.h"
#include "conform/toolpath/intersection/tool_safety.h"

namespace conform {

struct TubeJointSolveOptions {
  MeshIntersectionOptions intersection;
  // Azimuth ordering: a vertex this far behind (arc on the stub, mm) is dropped, farther fails [azimuth]. < 0:
  // automatic, kBacktrackEdges x the larger edge length + kBacktrackSigmas x the larger noise of the two scans near
  // the curve / sin(beta), beta the smallest angle between the surfaces there (scan_quality.h; noise sigma normal to
  // the surfaces moves the seam by sigma / sin(beta) along them), at least 0.05 mm.
  double backtrack_tolerance_mm = -1.0;
  // Intersection loops shorter than this fraction of the longest are dropped as noise islands (reported); a loop at
  // least this long fails [one-curve]. In [0, 1).
  double max_island_ratio = 0.2;
  // The facets alone can put the seam (s_leg + s_stub) / sin(beta) off, s = edge^2 x curvature / 8 the facet
  // sagitta of each scan near the seam: above this the meshes are too coarse for a path (exit 1, [coarse]).
  double max_facet_error_mm = 5.0;
  // Vertices closer than this fraction of a mesh's median edge length are one vertex (scanner meshes come unwelded:
  // a seam's vertices duplicated microns apart, which would be an open end (1a)). 0: only coincident ones. [0, 0.25].
  double weld_edge_fraction = 0.01;
  // 2 sigma of the seam tangent the scans' noise leaves (local surface fits, amplified by 1 / sin of the crossing
  // angle) above this anywhere on the path: the directions are not determined there (exit 1, [directions]).
  double max_direction_error_deg = 2.0;
  PathSamplingOptions sampling;          // azimuth or arc-length step; smoothing (applied before the azimuth test)
  JointGeometryOptions geometry;         // k nearest vertices per PCA normal
  ToolPathOptions tools;                 // groove angles, weld angle, standoffs
  ToolSafetyOptions safety;              // wall thicknesses: tools inside material fail the solution
  ProgressFn progress;                   // stages "intersect", "path", "normals"

  static constexpr double kBacktrackEdges = 0.5;
  static constexpr double kBacktrackSigmas = 4.0;
  static constexpr double kCoarseEdgeAngleDeg = 2.0;  // warn when a mesh's edges turn the normals more than this

  bool IsValid(std::string* error) const;
};

struct TubeJointSolution {
  bool ok = false;
  CurveCheck check;         // the failed condition when !ok (condition "safety" when a tool is inside material)
  std::string termination;  // "closed curve" or the check's message
  std::vector<std::string> warnings;  // islands dropped, coarse meshes, points not refined
  // Mesh welding (core/mesh_weld.h) before the intersection.
  std::size_t leg_welded_vertices = 0;
  std::size_t stub_welded_vertices = 0;
  double leg_weld_tolerance_mm = 0.0;  // weld_edge_fraction x the mesh's median edge length
  double stub_weld_tolerance_mm = 0.0;
  // Intersection figures.
  std::size_t segments = 0;          // triangle-pair segments
  std::size_t curve_vertices = 0;    // welded graph vertices
  std::size_t candidate_pairs = 0;   // triangle pairs tested exactly
  std::size_t islands = 0;           // loops dropped as noise islands
  double longest_island_mm = 0.0;
  std::size_t dropped_vertices = 0;  // dropped by the azimuth ordering (backtracks within the tolerance)
  std::size_t merged_vertices = 0;   // coincident neighbours merged, (1h)
  double backtrack_tolerance_mm = 0.0;  // the tolerance used
  double max_backtrack_mm = 0.0;        // the largest backtrack let pass
  ScanQuality leg_quality;              // noise, edge, curvature near the curve
  ScanQuality stub_quality;
  double min_crossing_deg = 90.0;       // the smallest angle between the surfaces at the quality samples
  double facet_error_mm = 0.0;          // the bound above, for these scans
  double normal_sigma_deg_max = 0.0;    // 1 sigma of the fitted normals (either mesh), largest over the path
  double tangent_sigma_deg_max = 0.0;   // 1 sigma of the seam tangent, largest over the path
  std::size_t refined_points = 0;       // path points moved onto the local fits (k_refine > 0)
  ToolSafetyResult safety;
  double intersection_seconds = 0.0;
  double total_seconds = 0.0;
  // The answer, in S. path's points, length and steps are those of the frames (the refined points written).
  SampledPath path;
  std::vector<PathFrame> frames;  // Eq. (4)
  ToolPaths tools;                // Eq. (10), (11)
};

// In memory: leg in L posed into S by T_S_L, stub in S. Throws conform::Error for invalid options or meshes.
TubeJointSolution solve_tube_joint(const Mesh& leg_L, const Mesh& stub_S, const Eigen::Isometry3d& T_S_L,
                                   const TubeJointSolveOptions& options);

struct TubeJointJobOptions {
  std::string leg_path;       // leg outer surface mesh, in L
  std::string stub_path;      // stub inner surface mesh, in S
  CadReadOptions cad;         // leg or stub as CAD (.step .stp .iges .igs): the tessellation (core/cad.h)
  TubeJointSpec spec;         // pitch, offset, protrusion: T_L_S (used when leg_pose_path is empty)
  std::string leg_pose_path;  // 4x4 text T_S_L (the leg's pose in S), instead of the spec
  // Markers (registration/tube_reference.h): CSV `x_mm,y_mm,z_mm,ref_x_mm,ref_y_mm,ref_z_mm`, a marker's position in
  // the scan and its known position in the tube's frame (L for the leg, S for the stub), >= 3 rows. Given, the mesh
  // is not taken to be in its frame: the frame comes from its cylinder fit plus the markers.
  std::string leg_markers_path;
  std::string stub_markers_path;
  double marker_tolerance_mm = 2.0;  // a marker farther than this from its known position: bad input (exit 2)
  TubeJointSolveOptions solve;
  std::string out_path;  // CSV of the quintuplets; empty: none
  std::string out_cut;   // CSV of the cutting poses; empty: none
  std::string out_weld;  // CSV of the welding poses; empty: none
  bool keep_geometry = false;  // keep both meshes (in their frames, markers applied) in the result (for a report)

  bool IsValid(std::string* error) const;
};

struct TubeJointJobResult {
  TubeJointSolution solution;
  Eigen::Isometry3d T_S_L = Eigen::Isometry3d::Identity();
  std::size_t leg_faces = 0;
  std::size_t stub_faces = 0;
  std::vector<CadReport> cad_inputs;  // leg and stub, those that were CAD
  std::vector<std::string> written;  // files written (none when !solution.ok)
  // Per marker file given: |T * marker - known position| of each marker, mm (empty when none was given).
  std::vector<double> leg_marker_residuals_mm;
  std::vector<double> stub_marker_residuals_mm;
  TubeReferenceResult leg_reference;   // method, residuals, the cylinder fit's disagreement (when markers given)
  TubeReferenceResult stub_reference;
  // Unit sanity: the stub's inner radius and the leg's outer radius measured on the meshes (median distance of the
  // vertices from each tube's axis, in its frame), mm.
  double stub_radius_mm = 0.0;
  double leg_radius_mm = 0.0;
  // With keep_geometry (else empty): the leg in L and the stub in S as intersected (pipelines/tube_joint/tube_joint_report.h).
  Mesh leg_L;
  Mesh stub_S;
};

// The frame of a scanned tube from a marker file and its cylinder fit (above). Throws conform::Error naming the file
// when it is malformed, has fewer than 3 markers, or the markers do not fit (a residual above the tolerance; the
// message lists the residuals).
TubeReferenceResult tube_frame_from_marker_file(const Mesh& mesh, const std::string& markers_path,
                                                double tolerance_mm);

// Throws conform::Error naming the file or option: unreadable meshes, a mesh without faces, NaN coordinates, an
// unwritable output, invalid options. A failed curve check is a result (solution.ok false), with no file written.
TubeJointJobResult run_tube_joint(const TubeJointJobOptions& options);

// CSV text. Path: `phi_rad,x_mm,y_mm,z_mm,tx,ty,tz,nsx,nsy,nsz,nlx,nly,nlz`; tools:
// `phi_rad,x_mm,y_mm,z_mm,dx,dy,dz,alpha_rad,psi_rad` (alpha: the groove angle alpha_c for the cut, the weld angle
// alpha_w for the weld; psi: the dihedral angle, tool_paths.h). 9 decimals, '\n' line ends.
std::string tube_joint_path_csv(const std::vector<PathFrame>& frames);
std::string tube_joint_tool_csv(const std::vector<ToolPose>& poses, const std::vector<double>& alpha_rad,
                                const std::vector<double>& psi_rad);

}  // namespace conform
