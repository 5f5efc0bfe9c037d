#include "conform/pipelines/inspect/inspect.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/cad_inputs.h"
#include "conform/core/constants.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/core/io.h"
#include "conform/core/normals.h"
#include "conform/core/output_set.h"
#include "conform/core/transform_io.h"
#include "conform/core/triangle_index.h"
#include "conform/core/units.h"
#include "conform/evaluation/deviation.h"
#include "conform/pipelines/align/align.h"
#include "conform/registration/icp.h"
#include "conform/registration/surface_noise.h"
#include "inspect/inspect_datums.h"
#include "inspect/inspect_feature_groups.h"
#include "inspect/inspect_features.h"
#include "inspect/inspect_faces_csv.h"
#include "inspect/inspect_tolerances.h"

namespace conform {

namespace {

std::string invalid_reason(const InspectOptions& o) {
  if (o.scan_path.empty()) return "no scan: give the scan file (--scan)";
  if (o.reference_path.empty()) return "no reference: give the CAD file (--reference)";
  if (!is_cad_file(o.reference_path)) {
    return "--reference " + o.reference_path + ": inspect needs the CAD's faces, a .step .stp .iges or .igs file";
  }
  if (o.best_fit && !o.transform_path.empty()) return "--transform and --align best-fit exclude each other";
  if (!(std::isfinite(o.mm_per_unit) && o.mm_per_unit > 0.0)) return "millimetres per unit must be finite and > 0";
  if (!(std::isfinite(o.max_distance_mm) && o.max_distance_mm >= 0.0)) {
    return "--max-distance must be >= 0 mm (0: automatic)";
  }
  if (!(o.max_normal_angle_rad > 0.0 && o.max_normal_angle_rad <= 1.5707963267948966)) {
    return "--max-normal-angle-deg must be in (0, 90]";
  }
  if (o.normal_neighbours < 5) return "the normals' neighbours must be >= 5";
  if (!(o.form_trim >= 0.0 && o.form_trim < 0.5)) return "--form-trim must be in [0, 0.5)";
  if (o.min_fit_points < 6) return "at least 6 points are needed to fit a feature";
  if (!o.tolerances_path.empty() && file_extension(o.tolerances_path) != ".csv") {
    return "--tolerances " + o.tolerances_path + ": must be .csv";
  }
  if (!o.out_faces_path.empty() && file_extension(o.out_faces_path) != ".csv") {
    return "--out-faces " + o.out_faces_path + ": must be .csv";
  }
  return "";
}

Mesh read_scan(const InspectOptions& options, InspectResult& result) {
  report(options.progress, "read scan", 0.0);
  ReadReport read;
  Mesh scan = read_geometry(options.scan_path, detail::read_options(NonFinitePolicy::kReject, options.cad), &read);
  result.warnings.insert(result.warnings.end(), read.warnings.begin(), read.warnings.end());
  if (scan.vertices.size() < 3) throw Error(options.scan_path + ": holds fewer than 3 points");
  detail::keep_cad_report(read, result.cad_inputs);
  if (options.mm_per_unit != 1.0 && !detail::cad_keeps_its_units(read, options.mm_per_unit, result.warnings)) {
    scale_in_place(scan, options.mm_per_unit);
  }
  report(options.progress, "read scan", 1.0);
  return scan;
}

// T_ref_scan from --align best-fit; false (with the verdict in result) when align does not trust its pose.
bool best_fit(const InspectOptions& options, InspectResult& result) {
  report(options.progress, "align", 0.0);
  AlignOptions align;
  align.scan_path = options.scan_path;
  align.reference_path = options.reference_path;
  align.scan_mm_per_unit = options.mm_per_unit;
  align.cad = options.cad;
  align.cad.save_mesh_path.clear();
  const AlignResult aligned = run_align(align);
  result.align_trust = to_string(aligned.verdict.trust);
  result.align_summary = aligned.verdict.summary;
  report(options.progress, "align", 1.0);
  if (aligned.verdict.trust == AlignTrust::kNo) return false;
  result.T_ref_scan = aligned.icp.T_ref_scan;
  return true;
}

// The face normal at p: the analytic surface's, or the nearest triangle's for other faces.
Eigen::Vector3d face_normal(const CadFaces& cad, const CadFace& face, const SurfacePoint& s, const Eigen::Vector3d& p) {
  if (is_analytic(face.type)) return analytic_outward_normal(face, p);
  const Face& t = cad.mesh.faces[static_cast<std::size_t>(s.face)];
  const Eigen::Vector3d& a = cad.mesh.vertices[static_cast<std::size_t>(t[0])];
  const Eigen::Vector3d& b = cad.mesh.vertices[static_cast<std::size_t>(t[1])];
  const Eigen::Vector3d& c = cad.mesh.vertices[static_cast<std::size_t>(t[2])];
  return (b - a).cross(c - a).normalized();
}

// Each point's face id (0: none) by its nearest triangle, within the distance cut and the normal check.
void assign_points(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                   const CadFaces& cad, const InspectOptions& options, InspectResult& result) {
  report(options.progress, "assign", 0.0);
  const TriangleIndex index(cad.mesh);
  const double min_cosine = std::cos(options.max_normal_angle_rad);
  result.point_face.assign(points.size(), 0);
  result.assigned = result.beyond_distance = result.normal_mismatch = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const SurfacePoint s = index.closest(points[i], result.max_distance_mm);
    if (!s.found()) {
      ++result.beyond_distance;
      continue;
    }
    const auto f = static_cast<std::size_t>(cad.triangle_face[static_cast<std::size_t>(s.face)]);
    const Eigen::Vector3d n = face_normal(cad, cad.faces[f], s, points[i]);
    if (!(std::abs(n.dot(normals[i])) >= min_cosine)) {
      ++result.normal_mismatch;
      continue;
    }
    result.point_face[i] = f + 1;
    ++result.assigned;
  }
  report(options.progress, "assign", 1.0);
}

// Deviations of the points on faces without an analytic surface: to the tessellation's smooth surface.
std::vector<double> mesh_deviations(const std::vector<Eigen::Vector3d>& points, const CadFaces& cad,
                                    const InspectResult& result) {
  std::vector<Eigen::Vector3d> off_analytic;
  std::vector<std::size_t> which;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t id = result.point_face[i];
    if (id != 0 && !is_analytic(cad.faces[id - 1].type)) {
      off_analytic.push_back(points[i]);
      which.push_back(i);
    }
  }
  std::vector<double> out(points.size(), std::numeric_limits<double>::quiet_NaN());
  if (off_analytic.empty()) return out;
  DeviationOptions deviation;
  deviation.smooth_surface = true;
  const DeviationResult d = compute_deviation(off_analytic, cad.mesh, deviation);
  for (std::size_t k = 0; k < which.size(); ++k) out[which[k]] = d.deviation_mm[k];
  return out;
}

void check_datum_ids(const InspectOptions& options, std::size_t face_count) {
  for (std::size_t k = 0; k < options.datum_faces.size(); ++k) {
    const std::size_t id = options.datum_faces[k];
    if (id < 1 || id > face_count) {
      throw Error("--datums: face " + std::to_string(id) + " is not one of the CAD's faces 1.." +
                  std::to_string(face_count));
    }
    for (std::size_t j = 0; j < k; ++j) {
      if (options.datum_faces[j] == id) throw Error("--datums: face " + std::to_string(id) + " is given twice");
    }
  }
}

// The faces of the feature a cylinder face belongs to (the face alone for other faces), 0-based.
std::vector<std::size_t> faces_with(const std::vector<std::vector<std::size_t>>& features, std::size_t face) {
  for (const std::vector<std::size_t>& group : features) {
    for (const std::size_t f : group) {
      if (f == face) return group;
    }
  }
  return {face};
}

// The 3-2-1 datum fit on the points assigned at the initial pose (a cylinder datum: its whole feature's); the scan
// and its normals moved by it, and assigned again.
void apply_datums(const CadFaces& cad, const std::vector<std::vector<std::size_t>>& features,
                  const InspectOptions& options, std::vector<Eigen::Vector3d>& points,
                  std::vector<Eigen::Vector3d>& normals, InspectResult& result) {
  std::vector<detail::DatumInput> datums;
  for (const std::size_t id : options.datum_faces) {
    detail::DatumInput d;
    d.face_id = id;
    const std::vector<std::size_t> group = faces_with(features, id - 1);
    d.nominal = group.size() > 1 ? detail::feature_nominal(cad.faces, group) : cad.faces[id - 1];
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (result.point_face[i] == 0) continue;
      if (std::find(group.begin(), group.end(), result.point_face[i] - 1) == group.end()) continue;
      d.points.push_back(points[i]);
      d.normals.push_back(normals[i]);
    }
    datums.push_back(std::move(d));
  }
  const detail::DatumFit fit = detail::fit_datums(datums);
  result.T_datum_initial = fit.T_datum_initial;
  result.datum_moved_mm = fit.moved_mm;
  result.T_ref_scan = fit.T_datum_initial * result.T_ref_scan;
  for (Eigen::Vector3d& p : points) p = fit.T_datum_initial * p;
  for (Eigen::Vector3d& n : normals) n = fit.T_datum_initial.linear() * n;
  assign_points(points, normals, cad, options, result);
}

// A cylinder whose nominal axis is the primary datum's normal (within 0.1 deg): how far its fitted axis leans.
void add_perpendicularity(const CadFace& primary, FaceInspection& f) {
  const double parallel = std::cos(radians(0.1));
  if (!f.fitted || f.nominal.type != CadSurfaceType::kCylinder) return;
  if (std::abs(f.nominal.axis.dot(primary.axis)) < parallel) return;
  f.perpendicularity_mm = f.length_mm * f.axis.cross(primary.axis).norm();
}

// A face's points, their normals and their deviations from it.
struct FacePoints {
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<double> deviation_mm;
};

void measure_features(const CadFaces& cad, const std::vector<std::vector<std::size_t>>& features,
                      const std::vector<FacePoints>& on_face, const InspectOptions& options, InspectResult& result) {
  result.features.clear();
  for (const std::vector<std::size_t>& group : features) {
    FeatureInspection feature;
    feature.id = result.features.size() + 1;
    FacePoints all;
    for (const std::size_t f : group) {
      feature.faces.push_back(f + 1);
      const FacePoints& some = on_face[f];
      all.points.insert(all.points.end(), some.points.begin(), some.points.end());
      all.normals.insert(all.normals.end(), some.normals.begin(), some.normals.end());
      all.deviation_mm.insert(all.deviation_mm.end(), some.deviation_mm.begin(), some.deviation_mm.end());
    }
    feature.measured.id = feature.id;
    feature.measured.nominal = detail::feature_nominal(cad.faces, group);
    detail::measure_face(all.points, all.normals, all.deviation_mm, options, feature.measured);
    result.features.push_back(std::move(feature));
  }
}

void measure_faces(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                   const CadFaces& cad, const std::vector<std::vector<std::size_t>>& features,
                   const InspectOptions& options, InspectResult& result) {
  report(options.progress, "faces", 0.0);
  const std::vector<double> to_mesh = mesh_deviations(points, cad, result);
  std::vector<FacePoints> on_face(cad.faces.size());
  result.deviation_mm.assign(points.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (result.point_face[i] == 0) continue;
    const std::size_t f = result.point_face[i] - 1;
    const CadFace& nominal = cad.faces[f];
    result.deviation_mm[i] = is_analytic(nominal.type) ? analytic_signed_distance(nominal, points[i]) : to_mesh[i];
    on_face[f].points.push_back(points[i]);
    on_face[f].normals.push_back(normals[i]);
    on_face[f].deviation_mm.push_back(result.deviation_mm[i]);
  }
  result.faces.resize(cad.faces.size());
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    FaceInspection& face = result.faces[f];
    face.id = f + 1;
    face.nominal = cad.faces[f];
    detail::measure_face(on_face[f].points, on_face[f].normals, on_face[f].deviation_mm, options, face);
    report(options.progress, "faces", static_cast<double>(f + 1) / static_cast<double>(cad.faces.size() + 1));
  }
  measure_features(cad, features, on_face, options, result);
  report(options.progress, "faces", 1.0);
}

// The best fit's correction of the initial pose. After --align best-fit: none (the initial pose is that fit). Without
// a transform: the fit --align best-fit makes (run_align on the scan as read, from where it is). After a transform:
// align's fine fit from that pose (point-to-surface ICP against the CAD's tessellation as inspect reads it, align's
// defaults against a mesh: every pair kept, the maximum distance kAlignAutoDistanceShare of the CAD's box diagonal).
// False when the fit is not trusted (align) or did not converge (ICP).
bool inspect_best_fit_correction(const std::vector<Eigen::Vector3d>& points, const Mesh& cad_mesh,
                                 const InspectOptions& quiet, const InspectResult& result,
                                 Eigen::Isometry3d& correction) {
  correction = Eigen::Isometry3d::Identity();
  if (result.alignment == "best-fit") return true;
  if (result.alignment == "none") {
    InspectResult aligned;
    if (!best_fit(quiet, aligned)) return false;
    correction = aligned.T_ref_scan;
    return true;
  }
  const IcpOptions fine = align_fine_options(AlignOptions(), default_align_method(true),
                                            kAlignAutoDistanceShare * bounding_box(cad_mesh).diagonal(), false);
  const IcpResult fit = icp(points, IcpReference(cad_mesh), Eigen::Isometry3d::Identity(), fine);
  if (!fit.converged) return false;
  correction = fit.T_ref_scan;
  return true;
}

// With datums: every figure again at the best fit (points at the initial pose, moved by the best fit's correction,
// assigned again), and how far that pose is from the datum frame.
void measure_at_best_fit(const CadFaces& cad, const std::vector<std::vector<std::size_t>>& features,
                         const InspectOptions& options, const std::vector<Eigen::Vector3d>& initial_points,
                         const std::vector<Eigen::Vector3d>& initial_normals, const Eigen::Isometry3d& T_initial,
                         InspectResult& result) {
  InspectBestFit& best = result.best_fit;
  best.computed = true;
  InspectOptions quiet = options;
  quiet.progress = nullptr;
  Eigen::Isometry3d correction;
  best.converged = inspect_best_fit_correction(initial_points, cad.mesh, quiet, result, correction);
  if (!best.converged) {
    result.warnings.push_back("the best fit beside the datum frame is not trusted or did not converge: no best-fit "
                              "figures");
    return;
  }
  best.T_ref_scan = correction * T_initial;
  best.angle_deg = degrees(Eigen::AngleAxisd(result.T_datum_initial.linear() * correction.linear().transpose()).angle());
  std::vector<Eigen::Vector3d> points(initial_points.size()), normals(initial_normals.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = correction * initial_points[i];
    normals[i] = correction.linear() * initial_normals[i];
    best.displacement_mm = std::max(best.displacement_mm, (result.T_datum_initial * initial_points[i] - points[i]).norm());
  }
  InspectResult at;
  at.max_distance_mm = result.max_distance_mm;
  assign_points(points, normals, cad, quiet, at);
  measure_faces(points, normals, cad, features, quiet, at);
  const CadFace& primary = cad.faces[options.datum_faces[0] - 1];
  for (FaceInspection& f : at.faces) add_perpendicularity(primary, f);
  for (FeatureInspection& f : at.features) add_perpendicularity(primary, f.measured);
  best.assigned = at.assigned;
  best.faces = std::move(at.faces);
  best.features = std::move(at.features);
}

// PCA normals of the scan's points (sign ignored by the normal check).
std::vector<Eigen::Vector3d> scan_normals(const Mesh& scan, int k) {
  NormalOptions pca;
  pca.k = k;
  std::vector<Eigen::Vector3d> normals;
  normals.reserve(scan.vertices.size());
  for (const auto& n : estimate_normals(to_cloud(scan), pca)) normals.emplace_back(n.normal_x, n.normal_y, n.normal_z);
  return normals;
}

// More than 5 % of the scan on no face is worth a line.
void warn_unassigned(InspectResult& result) {
  const double unassigned = static_cast<double>(result.scan_points - result.assigned);
  if (!(unassigned > 0.05 * static_cast<double>(result.scan_points))) return;
  char text[240];
  std::snprintf(text, sizeof text,
                "%.1f %% of the scan is on no face (%zu beyond %.3g mm, %zu with a normal not the face's): "
                "points off the part, or a larger deviation than the cut (raise --max-distance)",
                100.0 * unassigned / static_cast<double>(result.scan_points), result.beyond_distance,
                result.max_distance_mm, result.normal_mismatch);
  result.warnings.push_back(text);
}

void write_faces(const InspectOptions& options, InspectResult& result) {
  if (options.out_faces_path.empty()) return;
  report(options.progress, "write", 0.0);
  OutputSet outputs;
  detail::faces_csv(result).write(options.out_faces_path);
  outputs.commit();
  result.out_faces_path = options.out_faces_path;
  report(options.progress, "write", 1.0);
}

}  // namespace

bool InspectOptions::IsValid(std::string* error) const {
  const std::string why = invalid_reason(*this);
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

InspectResult run_inspect(const InspectOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  InspectResult result;
  Mesh scan = read_scan(options, result);
  result.scan_points = scan.vertices.size();
  report(options.progress, "read CAD", 0.0);
  CadReport cad_report;
  CadFaces cad = read_cad_faces(options.reference_path, options.cad, &cad_report, &result.warnings);
  result.cad_inputs.push_back(cad_report);
  report(options.progress, "read CAD", 1.0);
  // Read before the work, so that a bad file stops the job at once.
  const detail::Tolerances tolerances = options.tolerances_path.empty()
                                            ? detail::Tolerances()
                                            : detail::read_tolerances(options.tolerances_path, cad.faces);
  check_datum_ids(options, cad.faces.size());

  if (!options.transform_path.empty()) {
    result.alignment = "transform";
    result.T_ref_scan = read_transform(options.transform_path);
    result.T_ref_scan.translation() *= options.mm_per_unit;
  } else if (options.best_fit) {
    result.alignment = "best-fit";
    if (!best_fit(options, result)) {
      result.termination = "the best fit is not trusted: " + result.align_summary;
      return result;
    }
  }
  if (result.alignment != "none") scan = transformed(scan, result.T_ref_scan);

  result.scan_noise_mm = estimate_surface_noise(scan.vertices);
  result.max_distance_automatic = options.max_distance_mm == 0.0;
  result.max_distance_mm = result.max_distance_automatic
                               ? std::max(kInspectMinAutoDistanceMm, kInspectNoiseSigmas * result.scan_noise_mm)
                               : options.max_distance_mm;
  std::vector<Eigen::Vector3d> normals = scan_normals(scan, options.normal_neighbours);

  const std::vector<std::vector<std::size_t>> features = detail::cylinder_features(cad.faces);
  assign_points(scan.vertices, normals, cad, options, result);
  std::vector<Eigen::Vector3d> initial_points, initial_normals;  // with datums, for the best fit beside them
  const Eigen::Isometry3d T_initial = result.T_ref_scan;
  if (!options.datum_faces.empty()) {
    initial_points = scan.vertices;
    initial_normals = normals;
    apply_datums(cad, features, options, scan.vertices, normals, result);
  }
  measure_faces(scan.vertices, normals, cad, features, options, result);
  warn_unassigned(result);
  if (!options.datum_faces.empty()) {
    const CadFace& primary = cad.faces[options.datum_faces[0] - 1];
    for (FaceInspection& f : result.faces) add_perpendicularity(primary, f);
    for (FeatureInspection& f : result.features) add_perpendicularity(primary, f.measured);
    measure_at_best_fit(cad, features, options, initial_points, initial_normals, T_initial, result);
  }
  if (!tolerances.faces.empty() || !tolerances.features.empty()) detail::judge_tolerances(tolerances, result);
  result.ok = result.assigned > 0;
  result.termination = result.ok ? "ok" : "no scan point lies on a face of the CAD (is the scan in the part frame?)";
  write_faces(options, result);
  if (options.keep_geometry) {
    result.scan_ref = std::move(scan);
    result.reference = std::move(cad.mesh);
    result.reference_triangle_face = std::move(cad.triangle_face);
  }
  return result;
}

}  // namespace conform
