#pragma once
// How far each scan point lies from the reference: the signed distance to the reference mesh's surface (the closest
// point on its triangles, not on its vertices), or, when the reference is a point cloud, the unsigned distance to
// the nearest reference point.
//
//   DeviationOptions options;                                    // defaults: no distance limit
//   const DeviationResult d = compute_deviation(scan.vertices, reference, options);
//   const DeviationStatistics s = deviation_statistics(d.deviation_mm, {});   // statistics.h

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"
#include "conform/core/phong_surface.h"
#include "conform/core/progress.h"
#include "conform/core/triangle_index.h"

namespace conform {

struct DeviationOptions {
  // Scan points farther than this from the reference (mm) get no deviation (NaN) and count as unmatched: a scan that
  // covers more than the reference does. Infinite (the default): every point is matched.
  double max_distance_mm = std::numeric_limits<double>::infinity();
  // Measure to the smooth surface the reference's vertices and normals describe (core/phong_surface.h: Phong
  // tessellation, creases over 30 deg kept sharp), not to its flat facets, which lie inside a curved surface by up to
  // their chord error (a CAD tessellation's deflection; kappa h^2 / 8 on a mesh of edge h) and move the mean deviation
  // by about a third of it. Flat faces and sharp edges measure the same either way. False: the flat facets
  // (`compare --flat-facets`), the distance to the triangles exactly as they are.
  bool smooth_surface = true;
  ProgressFn progress;  // stage "deviation"

  // False (and why) when max_distance_mm is NaN or not > 0.
  bool IsValid(std::string* error) const;
};

enum class DeviationKind {
  kSignedToSurface,   // reference with faces: + on the side its normals point to (outside), - behind it
  kUnsignedToPoints,  // reference without faces: distance to the nearest reference point, >= 0
};

struct DeviationResult {
  // One per scan point, mm, in the scan's order; NaN for an unmatched point (beyond max_distance_mm).
  std::vector<double> deviation_mm;
  DeviationKind kind = DeviationKind::kSignedToSurface;
  std::size_t matched = 0;
  std::size_t unmatched = 0;
  // Where on the reference each point's deviation was measured: its closest surface point (or nearest reference
  // point); unset (NaN) for unmatched points.
  std::vector<Eigen::Vector3d> closest;
  // Against a mesh: the triangle each point's closest surface point lies on (the facet under the smooth surface's
  // point), -1 for unmatched points; empty against a cloud.
  std::vector<int> triangle;
  // For a reader of the result: what the numbers mean when that is not the default (e.g. a cloud reference gives
  // unsigned distances to points, which overestimate the distance to the surface by up to the point spacing).
  std::string note;

  bool is_signed() const { return kind == DeviationKind::kSignedToSurface; }
};

// Deviation of every scan point from the reference, a mesh (with faces: signed, to its surface) or a point cloud
// (a Mesh without faces: unsigned, to the nearest point). Both in the same frame, mm. Parallel over the points
// (OpenMP); the same input gives the same result whatever the thread count. Throws conform::Error for invalid
// options, an empty reference, or a scan or reference point with a NaN or infinite coordinate (naming its index).
DeviationResult compute_deviation(const std::vector<Eigen::Vector3d>& scan, const Mesh& reference,
                                  const DeviationOptions& options = {});

// As compute_deviation against a mesh, with a prebuilt index (e.g. one reference, many scans) and, for
// options.smooth_surface, its smooth surface over the same mesh (nullptr: the flat facets).
DeviationResult compute_deviation(const std::vector<Eigen::Vector3d>& scan, const TriangleIndex& reference,
                                  const PhongSurface* smooth, const DeviationOptions& options = {});

}  // namespace conform
