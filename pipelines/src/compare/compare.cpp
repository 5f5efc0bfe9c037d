#include "conform/pipelines/compare/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "conform/core/atomic_file.h"
#include "conform/core/cad.h"
#include "conform/core/cad_faces.h"
#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/core/io.h"
#include "conform/core/output_set.h"
#include "conform/core/transform_io.h"
#include "conform/core/units.h"
#include "conform/evaluation/cad_deviation.h"
#include "common/cad_inputs.h"

namespace conform {
namespace {

// How far (in chordal deflections of the tessellation) a point's exact-face distance may differ from its
// tessellation distance and still be taken: the chords lie within one deflection of the face.
constexpr double kExactFaceBoundDeflections = 2.0;

bool wrong_extension(const std::string& path, const char* extension) {
  return !path.empty() && file_extension(path) != extension;
}

std::string invalid_reason(const CompareOptions& o) {
  if (o.scan_path.empty()) return "no scan: give the scan file (--scan)";
  if (o.reference_path.empty()) return "no reference: give the reference file (--reference)";
  if (!(std::isfinite(o.scan_mm_per_unit) && o.scan_mm_per_unit > 0.0 && std::isfinite(o.reference_mm_per_unit) &&
        o.reference_mm_per_unit > 0.0)) {
    return "millimetres per unit of the scan and the reference must be finite and > 0";
  }
  if (o.tolerance_mm && !(std::isfinite(*o.tolerance_mm) && *o.tolerance_mm > 0.0)) {
    return "--tolerance must be > 0 mm, not " + std::to_string(*o.tolerance_mm);
  }
  if (!(o.max_distance_mm > 0.0)) return "the maximum distance must be > 0 mm";
  if (wrong_extension(o.out_deviation_path, ".ply"))
    return "--out-deviation " + o.out_deviation_path + ": must be .ply";
  if (wrong_extension(o.out_histogram_path, ".png"))
    return "--out-histogram " + o.out_histogram_path + ": must be .png";
  if (!o.out_histogram_path.empty() && !o.histogram) return "a histogram file was asked for but no renderer given";
  return "";
}

Mesh read_input(const std::string& path, double mm_per_unit, const CompareOptions& options, const char* stage,
                CompareResult& result) {
  const ProgressFn& progress = options.progress;
  std::vector<std::string>& warnings = result.warnings;
  report(progress, stage, 0.0);
  ReadReport report_;
  Mesh mesh = read_geometry(path, detail::read_options(NonFinitePolicy::kReject, options.cad), &report_);
  warnings.insert(warnings.end(), report_.warnings.begin(), report_.warnings.end());
  if (mesh.vertices.empty()) throw Error(path + ": holds no points");
  detail::keep_cad_report(report_, result.cad_inputs);
  if (mm_per_unit != 1.0 && !detail::cad_keeps_its_units(report_, mm_per_unit, warnings)) {
    scale_in_place(mesh, mm_per_unit);
  }
  report(progress, stage, 1.0);
  return mesh;
}

// A CAD reference with its faces (core/cad_faces.h): the tessellation the deviations are first measured to, and the
// exact faces they are then measured to. `mm_per_unit` does not apply (the file says its unit; a warning if given).
CadFaces read_cad_reference(const std::string& path, double mm_per_unit, const CompareOptions& options,
                            CompareResult& result) {
  report(options.progress, "read reference", 0.0);
  CadReport cad_report;
  std::vector<std::string> warnings;
  CadFaces cad = read_cad_faces(path, options.cad, &cad_report, &warnings);
  result.warnings.insert(result.warnings.end(), warnings.begin(), warnings.end());
  ReadReport read;
  read.cad = cad_report;
  detail::keep_cad_report(read, result.cad_inputs);
  detail::cad_keeps_its_units(read, mm_per_unit, result.warnings);
  report(options.progress, "read reference", 1.0);
  return cad;
}

// Doubts worth a line on stderr: sizes a thousand times apart (files in different units), or a scan that lies
// nowhere near the reference (not aligned: pass --transform).
void add_doubts(const Mesh& scan, const Mesh& reference, const CompareOptions& options, CompareResult& result) {
  const double scan_size = bounding_box(scan).diagonal();
  const double reference_size = bounding_box(reference).diagonal();
  const double ratio = std::max(scan_size, reference_size) / std::max(std::min(scan_size, reference_size), 1e-300);
  if (scan_size > 0.0 && reference_size > 0.0 && ratio > 100.0) {
    char text[200];
    std::snprintf(text, sizeof(text), "%.4g mm across, the reference %.4g mm: a factor of %.0f", scan_size,
                  reference_size, ratio);
    result.warnings.push_back("the scan is " + std::string(text) +
                              ". Are both in the units given? (--units sets both; --scan-units and --reference-units one each)");
  }
  if (result.statistics.count > 0 && std::abs(result.statistics.p50_mm) > 0.25 * reference_size) {
    result.warnings.push_back(
        "half the scan points are farther from the reference than a quarter of its size: is the scan in the "
        "reference frame? (" +
        std::string(options.transform_path.empty() ? "no --transform was given" : "check the --transform") + ")");
  }
}

// A mesh reference too coarse for the tolerance (or, without one, for the deviations measured): its faces that lie
// farther from the surface they approximate than the bar, named with what to do. The measurement stands.
void check_chord_error(const Mesh& reference, const CompareOptions& options, CompareResult& result) {
  const DeviationStatistics& s = result.statistics;
  const double bar = s.tolerance_mm ? kChordErrorShare * *s.tolerance_mm
                                    : std::max(kChordErrorShare * s.p95_abs_mm, kChordErrorFloorMm);
  const ChordErrorSummary c = summarize_chord_error(reference, estimate_chord_error(reference), bar);
  result.reference_chord_error = c;
  if (c.faces_over == 0) return;
  char text[600];
  std::snprintf(text, sizeof(text),
                "%s is too coarse for %s: its facets lie up to %.3g mm from the curved surface they approximate "
                "(estimated from the angles between neighbouring faces) on %zu faces, %.4g mm2 (%.1f %% of its area), "
                "beyond %.3g mm (half %s); deviations there can be off by as much. Export it finer (chordal "
                "deflection 0.005 mm or less) or give the STEP/IGES file",
                options.reference_path.c_str(), s.tolerance_mm ? "the tolerance" : "the deviations measured", c.max_mm,
                c.faces_over, c.area_over_mm2, c.area_mm2 > 0.0 ? 100.0 * c.area_over_mm2 / c.area_mm2 : 0.0, bar,
                s.tolerance_mm ? "the tolerance" : "the p95 of |d|, or 0.005 mm");
  result.warnings.emplace_back(text);
}

void write_outputs(const CompareOptions& options, const Mesh& scan_ref, CompareResult& result) {
  if (options.out_deviation_path.empty() && options.out_histogram_path.empty()) return;
  report(options.progress, "write", 0.0);
  // The picture first, in memory: a failure there leaves nothing on disk.
  const std::string png = options.out_histogram_path.empty()
                              ? std::string()
                              : options.histogram(result.deviation.deviation_mm, result.statistics);
  OutputSet outputs;  // the map and the histogram, both or neither
  if (!options.out_deviation_path.empty()) {
    VertexAttributes attributes;
    std::vector<float> values(result.deviation.deviation_mm.begin(), result.deviation.deviation_mm.end());
    attributes.scalars.push_back({"deviation_mm", std::move(values)});
    if (options.colour) {
      attributes.colors.reserve(scan_ref.vertices.size());
      for (double d : result.deviation.deviation_mm) attributes.colors.push_back(options.colour(d, result.statistics));
    }
    write_ply_with_attributes(options.out_deviation_path, scan_ref, attributes);
  }
  if (!options.out_histogram_path.empty()) write_file_atomically(options.out_histogram_path, png);
  outputs.commit();
  result.out_deviation_path = options.out_deviation_path;
  result.out_histogram_path = options.out_histogram_path;
  report(options.progress, "write", 1.0);
}

}  // namespace

bool CompareOptions::IsValid(std::string* error) const {
  const std::string why = invalid_reason(*this);
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

CompareResult run_compare(const CompareOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error(why);
  CompareResult result;
  Mesh scan = read_input(options.scan_path, options.scan_mm_per_unit, options, "read scan", result);
  if (!options.transform_path.empty()) {
    result.T_ref_scan = read_transform(options.transform_path);
    result.T_ref_scan.translation() *= options.reference_mm_per_unit;
    scan = transformed(scan, result.T_ref_scan);
  }
  // A CAD reference is measured to its exact faces (unless --flat-facets asks for the tessellation as it is).
  const bool exact = is_cad_file(options.reference_path) && !options.flat_facets;
  CadFaces cad;
  if (exact) cad = read_cad_reference(options.reference_path, options.reference_mm_per_unit, options, result);
  Mesh reference = exact ? cad.mesh
                         : read_input(options.reference_path, options.reference_mm_per_unit, options,
                                      "read reference", result);
  result.scan_points = scan.vertices.size();
  result.reference_points = reference.vertices.size();
  result.reference_faces = reference.faces.size();

  DeviationOptions deviation;
  deviation.max_distance_mm = options.max_distance_mm;
  // A CAD reference is first measured to its facets: the tessellator keeps them within the deflection of the faces,
  // so the exact face's figure is checked against a bound that holds, and a free-form face reads within it. The
  // smooth surface over a CAD tessellation has no such bound: a cylinder's strips (its whole height) whose rim meets
  // a tangent fillet took the fillet's tilted chord into the rim's normals and bulged 0.09 mm, beyond the check, so
  // the bulge was kept (a perfect filleted cylinder read 67 % out of a 0.05 mm tolerance).
  deviation.smooth_surface = !options.flat_facets && !exact;
  deviation.progress = options.progress;
  result.deviation = compute_deviation(scan.vertices, reference, deviation);
  if (exact) {
    // The facets lie within the deflection of the faces: a point whose two distances differ by more lies beyond its
    // face's trim and keeps the facets' figure.
    result.exact_points = to_exact_cad_faces(scan.vertices, cad, kExactFaceBoundDeflections *
                                                                     result.cad_inputs.back().deflection_mm,
                                             result.deviation);
  }
  DeviationStatisticsOptions statistics;
  statistics.tolerance_mm = options.tolerance_mm;
  result.statistics = deviation_statistics(result.deviation.deviation_mm, statistics);
  if (reference.has_faces() && !is_cad_file(options.reference_path)) check_chord_error(reference, options, result);
  add_doubts(scan, reference, options, result);
  write_outputs(options, scan, result);
  if (options.keep_geometry) {
    result.scan_ref = std::move(scan);
    result.reference = std::move(reference);
  }
  return result;
}

}  // namespace conform
