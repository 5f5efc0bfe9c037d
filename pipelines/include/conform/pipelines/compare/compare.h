#pragma once
// `conform compare`: how far a scan deviates from its reference, point by point and in summary. Reads the scan and
// the reference (a mesh: signed distances to its surface; a cloud: unsigned distances to its points), moves the scan
// into the reference frame by T_ref_scan when given, measures every scan point (evaluation/deviation.h) and
// summarises (evaluation/statistics.h), then writes the optional outputs: the deviation map (the scan in the
// reference frame with a per-vertex `deviation_mm` and colours, .ply) and the histogram (.png). The colour scale and
// the histogram picture are presentation: the caller (apps/) supplies them as functions. Outputs appear whole or
// not at all, all of them or none.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/cad.h"
#include "conform/core/mesh.h"
#include "conform/core/progress.h"
#include "conform/evaluation/chord_error.h"
#include "conform/evaluation/deviation.h"
#include "conform/evaluation/statistics.h"

namespace conform {

// RGB of one deviation (mm; NaN for an unmatched point), knowing the statistics of all (e.g. to scale the colours).
using DeviationColourFn = std::function<std::array<std::uint8_t, 3>(double deviation_mm, const DeviationStatistics&)>;
// A PNG file's bytes picturing all deviations.
using DeviationHistogramFn =
    std::function<std::string(const std::vector<double>& deviation_mm, const DeviationStatistics&)>;

// A mesh reference whose facets lie this share of the tolerance from the surface they approximate is reported as too
// coarse: where the smooth surface cannot restore the curve (chords over the crease angle, a bend in one or two
// chords) the deviations are off by up to that much.
constexpr double kChordErrorShare = 0.5;
// Without a tolerance the bar is the share of the p95 of |d|, but not below the CAD reader's default deflection.
constexpr double kChordErrorFloorMm = 0.005;

struct CompareOptions {
  std::string scan_path;       // cloud or mesh, any format read_geometry reads
  std::string reference_path;  // mesh or CAD, .step .stp .iges .igs (signed deviation), or cloud (unsigned)
  CadReadOptions cad;          // a CAD reference: its tessellation (core/cad.h)
  std::string transform_path;  // T_ref_scan (4x4 text) applied to the scan; empty: the scan is in the reference frame
  // Millimetres per unit of the scan, and of the reference and the transform's translation (a place in the
  // reference's frame); a CAD file keeps the units written in it.
  double scan_mm_per_unit = 1.0;
  double reference_mm_per_unit = 1.0;
  std::optional<double> tolerance_mm;  // the band +-t for the in/above/below shares; none by default
  double max_distance_mm = std::numeric_limits<double>::infinity();  // farther scan points are unmatched (NaN)
  // True: distances to the reference's flat triangles as they are; false: to the smooth surface its vertices and
  // normals describe (DeviationOptions::smooth_surface), free of the facets' chord error on curved surfaces, and
  // for a CAD reference to its exact analytic faces where a point lies over one.
  bool flat_facets = false;

  std::string out_deviation_path;  // .ply; empty: not written
  DeviationColourFn colour;        // the map's vertex colours; empty: the map has only `deviation_mm`
  std::string out_histogram_path;  // .png; empty: not written
  DeviationHistogramFn histogram;  // required with out_histogram_path

  ProgressFn progress;  // stages "read scan", "read reference", "deviation", "write"
  bool keep_geometry = false;  // keep the scan (reference frame) and the reference in the result, for a report

  // False (and why, naming the option) for a missing input path, a unit factor or distance that is not > 0, a
  // tolerance that is not > 0, an output with the wrong extension, or a histogram path without a renderer.
  bool IsValid(std::string* error) const;
};

struct CompareResult {
  std::size_t scan_points = 0;
  std::size_t reference_points = 0;
  std::size_t reference_faces = 0;                               // 0: the reference is a cloud, the deviations unsigned
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();  // as applied, translation in mm
  DeviationResult deviation;                                     // per scan point, in the scan's order
  // Against a CAD reference (without flat_facets): the points measured to an exact analytic face (plane, cylinder,
  // cone, sphere, torus; evaluation/cad_deviation.h); the others to the tessellation's smooth surface.
  std::size_t exact_points = 0;
  DeviationStatistics statistics;
  // Against a mesh reference (not CAD: its deflection is known): how far its facets may lie from the surface they
  // approximate (evaluation/chord_error.h), against the bar kChordErrorShare of the tolerance (of the p95 of |d|
  // without one, at least kChordErrorFloorMm); over it, a warning. Unset for a CAD or cloud reference.
  std::optional<ChordErrorSummary> reference_chord_error;
  std::vector<std::string> warnings;  // the readers' (ignored properties, ...) and doubts about units or placement
  std::vector<CadReport> cad_inputs;  // each CAD file read: units, bodies, deflection, triangles
  std::string out_deviation_path;     // the files written (empty when not asked for)
  std::string out_histogram_path;
  Mesh scan_ref;   // with options.keep_geometry: the scan in the reference frame, mm (else empty)
  Mesh reference;  // with options.keep_geometry: the reference as measured against, mm (else empty)
};

// Throws conform::Error naming the file or the option: invalid options, an unreadable or empty input, NaN/Inf
// coordinates, a transform file that is not a rigid transform, an output that cannot be written (and then
// no output is left behind).
CompareResult run_compare(const CompareOptions& options);

}  // namespace conform
