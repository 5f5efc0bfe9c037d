#pragma once
// `conform inspect` (issue 33): a scan inspected face by face against its CAD. Reads the CAD with its faces
// (core/cad_faces.h) and the scan, moves the scan into the part frame (a given T_ref_scan, or a best fit by
// pipelines/align/align.h), assigns each scan point to the CAD face it lies on (the face of its nearest triangle, if the
// point is within the distance cut and its normal agrees with the face's), and per face gives the signed deviation
// (to the exact analytic surface for planes, cylinders, cones, spheres and tori; to the tessellation's smooth surface
// for other faces), the form (the zone about the least-squares plane, cylinder, sphere, cone or torus) and the fitted
// feature against its nominal (a plane's normal, a cylinder's radius and axis, a cone's angle, a torus's radii); and
// per hole or boss (the cylindrical faces on one cylinder, merged) its size and position. Points on no face are
// counted, not forced onto one.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/cad.h"
#include "conform/core/cad_faces.h"
#include "conform/core/progress.h"
#include "conform/evaluation/form.h"
#include "conform/evaluation/statistics.h"

namespace conform {

struct InspectOptions {
  std::string scan_path;       // cloud or mesh, any format read_geometry reads
  std::string reference_path;  // CAD: .step .stp .iges .igs (the faces come from its B-rep)
  CadReadOptions cad;          // its tessellation (core/cad.h)
  std::string transform_path;  // T_ref_scan (4x4 text); empty: the scan is in the part frame (or best_fit)
  bool best_fit = false;       // align the scan to the CAD first (pipelines/align/align.h defaults); not with a transform
  double mm_per_unit = 1.0;    // millimetres per unit of the scan and the transform's translation; not the CAD

  // A point farther than this from the CAD's surface is on no face, mm; 0: automatic, the larger of
  // kInspectMinAutoDistanceMm and kInspectNoiseSigmas times the scan's own noise (registration/surface_noise.h).
  double max_distance_mm = 0.0;
  // A point whose normal (PCA over its scan neighbours, sign ignored) is farther than this from the face's outward
  // normal at the point is on no face, rad (30 deg): a point of a neighbouring face across an edge, or of a fixture.
  double max_normal_angle_rad = 0.5235987755982988;
  int normal_neighbours = 16;  // k of the scan's PCA normals
  // The form zone leaves out this share of a face's residuals, half at each end (evaluation/form.h): 1 %.
  double form_trim = 0.01;
  // Fewer points on a face: its deviation figures are given, its feature is not fitted (nor its form measured).
  std::size_t min_fit_points = 30;

  // Datum faces (ids, primary first; 1 to 3: a plane, then planes or cylinders, a cylinder standing for its whole
  // hole or boss): after the initial pose (transform, best fit or none) the scan is moved by the 3-2-1 datum fit
  // (pipelines/src/inspect/inspect_datums.h) and every figure is in the datum frame.
  std::vector<std::size_t> datum_faces;
  // .csv with a column face and any of lower_mm, upper_mm, form_mm, diameter_lower_mm, diameter_upper_mm, position_mm
  // (pipelines/src/inspect/inspect_tolerances.h): pass/fail per face and feature; empty: no verdict.
  std::string tolerances_path;
  std::string out_faces_path;  // .csv, one row per face; empty: not written
  bool keep_geometry = false;  // keep the scan (part frame) and the CAD's mesh in the result, for a report
  ProgressFn progress;         // stages "read scan", "read CAD", "align", "assign", "faces", "write"

  // False (and why, naming the option) for a missing input, a reference that is not CAD, a transform with best_fit,
  // a unit factor, distance, angle or trim out of range, or an out-faces path that is not .csv.
  bool IsValid(std::string* error) const;
};

constexpr double kInspectMinAutoDistanceMm = 0.5;
constexpr double kInspectNoiseSigmas = 20.0;

// A face's limits (--tolerances); an empty one is not toleranced.
struct FaceTolerance {
  std::size_t face_id = 0;
  std::optional<double> lower_mm;  // every point's deviation >= this
  std::optional<double> upper_mm;  // every point's deviation <= this
  std::optional<double> form_mm;   // form_mm (the trimmed zone) <= this
};

struct FaceVerdict {
  FaceTolerance tolerance;
  bool measured = false;      // false: no points on the face (or no form where one is toleranced): no verdict
  bool profile_pass = false;  // min and max deviation within [lower, upper]
  bool form_pass = false;
  bool pass = false;
};

// A feature's limits (--tolerances, on a row naming one of its faces); an empty one is not toleranced.
struct FeatureTolerance {
  std::size_t face_id = 0;                  // the row's face, one of the feature's
  std::optional<double> diameter_lower_mm;  // the fitted diameter >= this
  std::optional<double> diameter_upper_mm;  // the fitted diameter <= this
  std::optional<double> position_mm;        // position_mm (a diameter zone about the nominal axis) <= this
};

struct FeatureVerdict {
  FeatureTolerance tolerance;
  bool measured = false;  // false: no fitted cylinder (too few points, or the fit failed): no verdict
  bool size_pass = false;
  bool position_pass = false;
  bool pass = false;
};

// One CAD face as measured.
struct FaceInspection {
  std::size_t id = 0;  // 1-based, the face's place in the file (bodies in order)
  CadFace nominal;
  std::size_t points = 0;  // scan points assigned to it
  bool exact = false;      // deviations to the exact analytic surface (else to the tessellation's smooth surface)
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();  // of its points
  DeviationStatistics deviation;                          // signed, + outside; count 0 without points

  // The form: the zone of the residuals about `form_reference` ("least-squares plane", "least-squares cylinder",
  // "least-squares sphere", or
  // "nominal surface" where no feature is fitted); measured = false with fewer than min_fit_points points.
  bool form_measured = false;
  std::string form_reference;
  FormZone form;

  // The fitted feature (planes, cylinders and spheres with enough points); fit_note says why not when fitted is false.
  bool fitted = false;
  std::string fit_note;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // plane: fitted, oriented like the nominal (outward)
  double angle_to_nominal_deg = 0.0;                 // plane: between fitted and nominal normals
  double plane_offset_mm = 0.0;  // plane: the fitted plane's distance from the nominal at the face's centre, + out
  double radius_mm = 0.0;        // cylinder, sphere: fitted; torus: major; cone: at the nominal's middle section
  double nominal_radius_mm = 0.0;  // cone: the nominal's radius at that section (else the nominal's radius)
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // sphere, torus: fitted centre
  double centre_offset_mm = 0.0;  // sphere, torus: from the nominal centre
  double minor_radius_mm = 0.0;   // torus: fitted
  double half_angle_deg = 0.0;    // cone: fitted
  Eigen::Vector3d apex_mm = Eigen::Vector3d::Zero();  // cone: fitted
  double radius_std_mm = 0.0;    // cylinder: its standard deviation from the fit (fitting/cylinder.h)
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();        // cylinder, cone, torus: fitted, oriented like the nominal
  // cylinder, cone: the fitted axis's point nearest the nominal's
  Eigen::Vector3d axis_point_mm = Eigen::Vector3d::Zero();
  double axis_offset_mm = 0.0;   // cylinder, cone: from the nominal axis point at the face's middle to the fitted axis
  double axis_angle_deg = 0.0;   // cylinder, cone, torus: between the fitted and the nominal axis
  double length_mm = 0.0;        // cylinder: the span of its points along the fitted axis
  // cylinder: twice the larger distance of the fitted axis's ends (at the points' span) from the nominal axis: the
  // diameter of the smallest zone about the nominal axis holding the fitted axis (ISO 1101 position, in the frame of
  // the inspection: the datum frame with --datums)
  double position_mm = 0.0;
  // cylinder, with a primary datum plane its axis is nominally perpendicular to: length_mm x sin(the fitted axis's
  // angle from the datum's normal), the diameter of the zone perpendicular to the datum holding the axis; NaN else
  double perpendicularity_mm = std::numeric_limits<double>::quiet_NaN();

  std::optional<FaceVerdict> verdict;  // with --tolerances, for the faces it names
};

// A hole or boss: the cylindrical faces on one cylinder (a CAD kernel may split one into two or more faces;
// pipelines/src/inspect/inspect_feature_groups.h), measured as one on all their points. `measured` holds the figures
// of a cylinder face (its nominal the merged faces'); with --datums, in the datum frame.
struct FeatureInspection {
  std::size_t id = 0;              // 1-based, in the order of the features' first faces
  std::vector<std::size_t> faces;  // its face ids, ascending
  FaceInspection measured;
  std::optional<FeatureVerdict> verdict;  // with --tolerances naming one of its faces with a size or position limit
};

// With datums, the figures beside the datum frame's at the best fit: the initial pose itself after --align best-fit,
// else point-to-surface ICP against the CAD started from the initial pose (align's fine fit against a mesh,
// pipelines/align/align.h defaults). Every point is assigned again at that pose; no tolerances are judged there.
struct InspectBestFit {
  bool computed = false;   // datums were given
  bool converged = false;  // false: the ICP did not converge; no figures
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // the best fit's pose, mm
  double displacement_mm = 0.0;  // the largest distance of a scan point between the datum frame and the best fit
  double angle_deg = 0.0;        // the turn between the two poses
  std::size_t assigned = 0;      // points on some face at the best fit
  std::vector<FaceInspection> faces;        // as InspectResult::faces, at the best fit
  std::vector<FeatureInspection> features;  // as InspectResult::features, at the best fit
};

struct InspectResult {
  std::size_t scan_points = 0;
  std::size_t assigned = 0;          // points on some face
  std::size_t beyond_distance = 0;   // on no face: farther than the distance cut from the CAD
  std::size_t normal_mismatch = 0;   // on no face: within the cut, their normal not the face's
  double scan_noise_mm = 0.0;        // the scan's own noise (registration/surface_noise.h)
  double max_distance_mm = 0.0;      // as used
  bool max_distance_automatic = false;
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // as applied, mm
  std::string alignment = "none";    // "none", "transform", "best-fit"
  std::string align_trust;           // best-fit: "yes", "check" or "no" (pipelines/align/align.h); "no" stops the job
  std::string align_summary;
  // With datums: the correction the datum fit applied on top of the initial pose (T_ref_scan includes it), and how
  // far each datum's fitted plane moved along its nominal normal, mm.
  Eigen::Isometry3d T_datum_initial = Eigen::Isometry3d::Identity();
  std::vector<double> datum_moved_mm;
  InspectBestFit best_fit;           // with datums: the figures at the best fit, beside the datum frame's
  bool ok = false;                   // the job ran to its figures (false: best fit refused, or no point assigned)
  std::string termination;           // "ok", or why not
  std::vector<FaceInspection> faces;   // every face of the CAD, by id
  std::vector<FeatureInspection> features;  // every hole and boss (cylinder) of the CAD, measured or not
  std::vector<std::size_t> point_face;  // per scan point: its face's id, 0 for none
  std::vector<double> deviation_mm;     // per scan point: its deviation from its face, NaN for none
  std::vector<std::string> warnings;
  std::vector<CadReport> cad_inputs;
  std::string out_faces_path;         // written; empty when not
  // With tolerances: "pass" (every toleranced face and feature measured and within), "fail" (one is not),
  // "incomplete" (none fails, one is not measured); empty without.
  std::string verdict;
  Mesh scan_ref;   // with options.keep_geometry: the scan's points in the part (datum) frame, mm
  Mesh reference;  // with options.keep_geometry: the CAD's tessellation, mm
  std::vector<std::int32_t> reference_triangle_face;  // with keep_geometry: per triangle of reference, its face index
};

// Throws conform::Error naming the file or option: invalid options, an unreadable or empty scan, a reference that is
// not CAD or not readable, a transform that is not rigid, an output that cannot be written (nothing left behind).
InspectResult run_inspect(const InspectOptions& options);

}  // namespace conform
