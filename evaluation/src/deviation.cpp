// Deviation of scan points from a reference: signed point-to-surface distance through TriangleIndex (sign from the
// angle-weighted pseudo-normal at the closest point, Baerentzen & Aanaes 2005), moved onto the smooth surface of
// PhongSurface where the reference is curved, or unsigned point-to-point distance through KdTree when the reference
// has no faces.

#include "conform/core/constants.h"
#include "conform/evaluation/deviation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {

bool DeviationOptions::IsValid(std::string* error) const {
  if (max_distance_mm > 0.0) return true;  // also false for NaN
  if (error != nullptr) *error = "max_distance_mm must be > 0 mm (or infinite), not " + std::to_string(max_distance_mm);
  return false;
}

namespace {

// Points per progress report; each chunk is spread over the threads.
constexpr std::size_t kChunk = std::size_t{1} << 16;

void check_finite(const std::vector<Eigen::Vector3d>& points, const char* what) {
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw Error(std::string(what) + " point " + std::to_string(i) + " has a NaN or infinite coordinate");
    }
  }
}

void check_options(const DeviationOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("deviation options: " + why);
}

// measure(i) for every point, in parallel chunks, reporting progress from this thread between chunks. Each point is
// measured on its own, so the result does not depend on the thread count.
template <typename Measure>
void for_each_point(std::size_t n, const ProgressFn& progress, Measure&& measure) {
  report(progress, "deviation", 0.0);
  for (std::size_t begin = 0; begin < n; begin += kChunk) {
    const auto first = static_cast<std::int64_t>(begin);
    const auto last = static_cast<std::int64_t>(std::min(n, begin + kChunk));
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t i = first; i < last; ++i) measure(static_cast<std::size_t>(i));
    report(progress, "deviation", static_cast<double>(last) / static_cast<double>(n));
  }
  if (n == 0) report(progress, "deviation", 1.0);
}

void count_matches(DeviationResult& result) {
  result.matched = static_cast<std::size_t>(
      std::count_if(result.deviation_mm.begin(), result.deviation_mm.end(), [](double d) { return !std::isnan(d); }));
  result.unmatched = result.deviation_mm.size() - result.matched;
}

// The nearest reference point in double precision (ties to the lower index), as a brute-force loop would find it:
// the tree searches in float, so every point within the float answer's distance plus its rounding is compared.
int nearest_in_double(const KdTree& tree, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p) {
  const Eigen::Vector3f query = p.cast<float>();
  float sq = 0.0f;
  int best = tree.nearest(query, &sq);
  double best_sq = (p - points[static_cast<std::size_t>(best)]).squaredNorm();
  // Rounding the coordinates to float moves a distance by at most a few float steps of the coordinates' size.
  const double margin = 1e-6 * (1.0 + p.cwiseAbs().maxCoeff() + std::sqrt(static_cast<double>(sq)));
  const auto radius = static_cast<float>(std::sqrt(static_cast<double>(sq)) + margin);
  thread_local std::vector<int> candidates;
  thread_local std::vector<float> sq_distances;
  tree.radius(query, radius, candidates, sq_distances);
  for (int c : candidates) {
    const double d2 = (p - points[static_cast<std::size_t>(c)]).squaredNorm();
    if (d2 < best_sq || (d2 == best_sq && c < best)) {
      best = c;
      best_sq = d2;
    }
  }
  return best;
}

DeviationResult point_deviation(const std::vector<Eigen::Vector3d>& scan, const Mesh& reference,
                                const DeviationOptions& options) {
  check_finite(reference.vertices, "reference");
  const KdTree tree(reference.vertices);
  DeviationResult result;
  result.kind = DeviationKind::kUnsignedToPoints;
  result.note =
      "the reference has no faces: deviations are unsigned distances to the nearest reference point, not to a "
      "surface, and read high by up to about half the reference's point spacing";
  result.deviation_mm.assign(scan.size(), kNaN);
  result.closest.assign(scan.size(), Eigen::Vector3d::Constant(kNaN));
  for_each_point(scan.size(), options.progress, [&](std::size_t i) {
    const int nearest = nearest_in_double(tree, reference.vertices, scan[i]);
    const Eigen::Vector3d& q = reference.vertices[static_cast<std::size_t>(nearest)];
    const double d = (scan[i] - q).norm();
    if (d <= options.max_distance_mm) {
      result.deviation_mm[i] = d;
      result.closest[i] = q;
    }
  });
  count_matches(result);
  return result;
}

}  // namespace

DeviationResult compute_deviation(const std::vector<Eigen::Vector3d>& scan, const TriangleIndex& reference,
                                  const PhongSurface* smooth, const DeviationOptions& options) {
  check_options(options);
  check_finite(scan, "scan");
  DeviationResult result;
  result.kind = DeviationKind::kSignedToSurface;
  result.deviation_mm.assign(scan.size(), kNaN);
  result.closest.assign(scan.size(), Eigen::Vector3d::Constant(kNaN));
  result.triangle.assign(scan.size(), -1);
  for_each_point(scan.size(), options.progress, [&](std::size_t i) {
    const SurfacePoint s = reference.closest(scan[i], options.max_distance_mm);
    if (!s.found()) return;
    result.triangle[i] = s.face;
    const PhongPoint lifted = smooth != nullptr && options.smooth_surface ? smooth->nearest(scan[i], s) : PhongPoint{};
    if (lifted.lifted) {
      // On the smooth surface the side is the one its normal points to: a point between a facet and the curved
      // surface above it is inside; beside a rim, the flat face's plane reaches to the curved side's lifted edge
      // (PhongSurface::nearest), so a point under a cap's rim is signed by the cap, not by the side.
      const double d = (scan[i] - lifted.point).norm();
      result.deviation_mm[i] = (scan[i] - lifted.point).dot(lifted.normal) < 0.0 ? -d : d;
      result.closest[i] = lifted.point;
      return;
    }
    const double d = std::sqrt(s.sq_distance);
    // The pseudo-normal's side (Baerentzen & Aanaes 2005, Theorem 1); a point on the surface counts as +0.
    result.deviation_mm[i] = (scan[i] - s.point).dot(reference.normal_at(s)) < 0.0 ? -d : d;
    result.closest[i] = s.point;
  });
  count_matches(result);
  return result;
}

DeviationResult compute_deviation(const std::vector<Eigen::Vector3d>& scan, const Mesh& reference,
                                  const DeviationOptions& options) {
  check_options(options);
  check_finite(scan, "scan");
  if (reference.vertices.empty()) throw Error("reference: holds no points to measure the deviation from");
  if (!reference.has_faces()) return point_deviation(scan, reference, options);
  const TriangleIndex index(reference);
  if (!options.smooth_surface) return compute_deviation(scan, index, nullptr, options);
  const std::vector<Eigen::Vector3d> no_normals;
  const PhongSurface smooth(reference, reference.has_normals() ? reference.normals : no_normals);
  return compute_deviation(scan, index, &smooth, options);
}

}  // namespace conform
