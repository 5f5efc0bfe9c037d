#include "conform/registration/coarse_fpfh.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "conform/core/cloud.h"
#include "conform/core/error.h"
#include "conform/core/normals.h"
#include "conform/core/parallel.h"
#include "conform/registration/downsample.h"
#include "conform/registration/feature_ransac.h"
#include "fpfh_features.h"

namespace conform {

namespace {

constexpr std::size_t kMinPoints = 10;
constexpr int kNormalNeighbours = 16;
constexpr double kMinPointsPerVoxel = 4.0;  // the automatic voxel: at least 2 point spacings on a surface
// Stray points are removed on a first voxel grid this much finer than the features' (a tenth of the points' cost;
// a stray point stays alone in its small voxel, a cluster of copies becomes one point, alone).
constexpr double kCleaningVoxel = 1.0 / 3.0;

struct Described {
  std::vector<Eigen::Vector3f> points;   // relative to the side's origin
  std::vector<Eigen::Vector3f> normals;  // turned away from the side's centroid
  std::vector<detail::FpfhHistogram> features;
};

// The points whose mean distance to their `k` nearest neighbours is within `sigmas` standard deviations of the mean
// over all points (fpfh_features.h): stray returns off the surface, each alone in its voxel, would otherwise be as
// many downsampled points as the surface has and scramble its normals and histograms.
std::vector<Eigen::Vector3d> without_outliers(const std::vector<Eigen::Vector3d>& input, const Eigen::Vector3d& origin,
                                              int k, double sigmas) {
  if (k <= 0 || input.size() <= static_cast<std::size_t>(k)) return input;
  std::vector<Eigen::Vector3f> local;
  local.reserve(input.size());
  for (const Eigen::Vector3d& p : input) local.push_back((p - origin).cast<float>());
  std::vector<Eigen::Vector3d> out;
  for (const std::size_t i : detail::statistical_inliers(local, k, sigmas)) out.push_back(input[i]);
  return out;
}

// Downsampled points, relative to `origin` so that float keeps their precision, with their FPFH descriptors.
Described describe(const std::vector<Eigen::Vector3d>& input, const Eigen::Vector3d& origin, double voxel_mm,
                   double radius_mm, const FpfhOptions& options, const char* what) {
  const std::vector<Eigen::Vector3d> down =
      voxel_downsample(without_outliers(voxel_downsample(input, kCleaningVoxel * voxel_mm), origin,
                                        options.outlier_neighbours, options.outlier_sigmas),
                       voxel_mm);
  if (down.size() < kMinPoints) {
    throw Error(std::string("FPFH: the ") + what + " has " + std::to_string(down.size()) + " points after " +
                std::to_string(voxel_mm) + " mm voxels; at least " + std::to_string(kMinPoints) +
                " are needed (a smaller voxel?)");
  }
  Cloud cloud;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : down) {
    const Eigen::Vector3f q = (p - origin).cast<float>();
    cloud.points.push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
    mean += p - origin;
  }
  NormalOptions normal_options;
  normal_options.k = kNormalNeighbours;
  normal_options.viewpoint = mean / static_cast<double>(down.size());
  const pcl::PointCloud<pcl::Normal> normals = estimate_normals(cloud, normal_options);
  Described d;
  d.points.reserve(down.size());
  d.normals.reserve(down.size());
  for (std::size_t i = 0; i < down.size(); ++i) {
    d.points.push_back(cloud.points[i].getVector3fMap());
    // Away from the centroid rather than towards it: the same rule on both sides keeps the histograms comparable.
    d.normals.push_back(-normals[i].getNormalVector3fMap());
  }
  d.features = detail::fpfh_histograms(d.points, d.normals, static_cast<float>(radius_mm));
  return d;
}

struct Matches {
  std::vector<std::pair<int, int>> all;   // every scan point with its nearest reference feature
  std::vector<std::pair<int, int>> kept;  // those that pass the filters
};

// Correspondences (scan point, reference point of the nearest feature) and those that pass the filters: mutual (the
// scan feature nearest to that reference feature is the scan's own) and the ratio test (nearest over second-nearest
// feature distance below `ratio`, Lowe 2004).
Matches matched(const std::vector<detail::FpfhHistogram>& scan, const std::vector<detail::FpfhHistogram>& reference,
                bool mutual, double ratio) {
  const detail::HistogramIndex in_reference(reference);
  const detail::HistogramIndex in_scan(scan);
  // Per scan point: its nearest reference feature (-1: none) and whether the pair passes the filters; searched in
  // parallel, collected in scan order.
  const std::size_t n = scan.size();
  std::vector<int> nearest(n, -1);
  std::vector<char> passes(n, 0);
#pragma omp parallel
  {
    std::vector<std::size_t> index, back;
    std::vector<float> distance, back_distance;
#pragma omp for schedule(dynamic, 64)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(n); ++k) {
      const auto i = static_cast<std::size_t>(k);
      const detail::FpfhHistogram& f = scan[i];
      if (!std::isfinite(f[0])) continue;
      in_reference.knn(f, 2, index, distance);
      if (index.size() < 2) continue;
      nearest[i] = static_cast<int>(index[0]);
      if (ratio > 0.0 && !(std::sqrt(distance[0]) < ratio * std::sqrt(distance[1]))) continue;
      if (mutual) {
        in_scan.knn(reference[index[0]], 1, back, back_distance);
        if (back.empty() || back[0] != i) continue;
      }
      passes[i] = 1;
    }
  }
  Matches out;
  for (std::size_t i = 0; i < n; ++i) {
    if (nearest[i] < 0) continue;
    out.all.emplace_back(static_cast<int>(i), nearest[i]);
    if (passes[i] != 0) out.kept.emplace_back(static_cast<int>(i), nearest[i]);
  }
  return out;
}

std::vector<Eigen::Vector3d> as_vectors(const std::vector<Eigen::Vector3f>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const Eigen::Vector3f& p : points) out.push_back(p.cast<double>());
  return out;
}

// How many voxels of size v hold points: their cells packed into one 64-bit key each (21 bits an axis, from the
// lowest cell), sorted; voxel_downsample's count when the cloud spans more than 2^21 cells.
double occupied_voxels(const std::vector<Eigen::Vector3d>& points, double v) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  const Eigen::Vector3d low = (box.min() / v).array().floor();
  if (!(((box.max() / v).array().floor() - low.array()).maxCoeff() < 2097151.0)) {
    return static_cast<double>(voxel_downsample(points, v).size());
  }
  std::vector<std::uint64_t> keys;
  keys.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d c = (p / v).array().floor() - low.array();
    keys.push_back(static_cast<std::uint64_t>(c.x()) << 42 | static_cast<std::uint64_t>(c.y()) << 21 |
                   static_cast<std::uint64_t>(c.z()));
  }
  std::sort(keys.begin(), keys.end());
  return static_cast<double>(std::unique(keys.begin(), keys.end()) - keys.begin());
}

// From the data: the voxel that leaves about `target` points on the side with less surface (the overlap is at most
// that side's surface, and the features must resolve its shape: 1/30 of the reference's diagonal, the rule before,
// left a ribbed plate's 6 mm ribs one voxel wide and 5 % of the matches right), and at least 2 point spacings on
// both sides (4 points a voxel), so that a voxel holds points and a histogram holds neighbours. A surface leaves
// about area / voxel^2 points: two passes from 1/30 of the reference's diagonal find the size.
double auto_voxel(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& reference,
                  std::size_t target) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : reference) box.extend(p);
  double v = box.diagonal().norm() / 30.0;
  const auto count = [&](const std::vector<Eigen::Vector3d>& points) { return occupied_voxels(points, v); };
  for (int pass = 0; pass < 2; ++pass)
    v *= std::sqrt(std::min(count(scan), count(reference)) / static_cast<double>(target));
  double floor = v;
  for (const std::vector<Eigen::Vector3d>* side : {&scan, &reference}) {
    const double per_voxel = static_cast<double>(side->size()) / count(*side);
    if (per_voxel < kMinPointsPerVoxel) floor = std::max(floor, v * std::sqrt(kMinPointsPerVoxel / per_voxel));
  }
  return floor;
}

}  // namespace

bool FpfhOptions::IsValid(std::string* error) const {
  std::string why;
  if (!(voxel_mm >= 0.0) || !std::isfinite(voxel_mm)) {
    why = "voxel_mm must be finite and >= 0 (0: automatic)";
  } else if (!(feature_radius > 1.0) || !std::isfinite(feature_radius)) {
    why = "feature_radius must be finite and > 1 voxel";
  } else if (!(inlier_distance > 0.0) || !std::isfinite(inlier_distance)) {
    why = "inlier_distance must be finite and > 0 voxels";
  } else if (!(min_inlier_fraction >= 0.0 && min_inlier_fraction <= 1.0)) {
    why = "min_inlier_fraction must be in [0, 1]";
  } else if (target_points < kMinPoints) {
    why = "target_points must be >= " + std::to_string(kMinPoints);
  } else if (hypotheses < 1) {
    why = "hypotheses must be >= 1";
  } else if (max_iterations < 1) {
    why = "max_iterations must be >= 1";
  } else if (!(confidence > 0.0 && confidence <= 1.0)) {
    why = "confidence must be in (0, 1]";
  } else if (!(ratio >= 0.0 && ratio <= 1.0)) {
    why = "ratio must be in [0, 1] (0: no ratio test)";
  } else if (outlier_neighbours < 0 || !(outlier_sigmas > 0.0) || !std::isfinite(outlier_sigmas)) {
    why = "outlier_neighbours must be >= 0 (0: no outlier removal) and outlier_sigmas finite and > 0";
  } else if (min_matched_points < 3) {
    why = "min_matched_points must be >= 3";
  } else if (!(narrow_feature_radius == 0.0 ||
               (narrow_feature_radius > 1.0 && narrow_feature_radius < feature_radius))) {
    why = "narrow_feature_radius must be 0 (none) or in (1, feature_radius) voxels";
  } else if (!(similarity >= 0.0 && similarity < 1.0)) {
    why = "similarity must be in [0, 1)";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

FpfhResult fpfh_ransac(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& reference,
                       const FpfhOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("FPFH options: " + why);
  if (reference.empty() || scan.empty()) throw Error("FPFH: the scan or the reference has no points");
  FpfhResult result;
  result.voxel_mm = options.voxel_mm > 0.0 ? options.voxel_mm : auto_voxel(scan, reference, options.target_points);
  const double v = result.voxel_mm;
  // Each side relative to its own first point: the features are computed in float.
  const Eigen::Vector3d scan_origin = scan.front(), ref_origin = reference.front();
  // The two sides at once, one a thread: most of describe() (voxels, outlier removal, normals) runs on one thread.
  // Each side's result is the same either way; the scan's error, if both fail, is the one reported, as before.
  Described s, r;
  for_each_in_parallel(2, [&](std::size_t side) {
    if (side == 0) {
      s = describe(scan, scan_origin, v, options.feature_radius * v, options, "scan");
    } else {
      r = describe(reference, ref_origin, v, options.feature_radius * v, options, "reference");
    }
  });
  result.scan_points = s.points.size();
  result.reference_points = r.points.size();
  result.feature_radius_mm = options.feature_radius * v;

  Matches found_matches = matched(s.features, r.features, options.mutual, options.ratio);
  const bool filtered = options.mutual || options.ratio > 0.0;
  if (filtered && found_matches.kept.size() < options.min_matched_points && options.narrow_feature_radius > 0.0) {
    // Few features match both ways: the two sides' histograms of the same places differ. The usual cause is a
    // support wider than the part's walls where the scan sees one side of them: the reference's histograms then
    // hold the far faces too (a one-side scan of 10 mm plates at a 19 mm radius). Narrower supports, the
    // same points and normals; kept when more of them match both ways.
    const float narrow = static_cast<float>(options.narrow_feature_radius * v);
    const std::vector<detail::FpfhHistogram> s_narrow = detail::fpfh_histograms(s.points, s.normals, narrow),
                                             r_narrow = detail::fpfh_histograms(r.points, r.normals, narrow);
    Matches narrow_matches = matched(s_narrow, r_narrow, options.mutual, options.ratio);
    if (narrow_matches.kept.size() > found_matches.kept.size()) {
      found_matches = std::move(narrow_matches);
      result.feature_radius_mm = options.narrow_feature_radius * v;
    }
  }
  result.filtered_points = found_matches.kept.size();
  // The filters are a help, not a condition: every nearest-feature pair when too few pass them.
  const std::vector<std::pair<int, int>>& matches =
      found_matches.kept.size() >= options.min_matched_points ? found_matches.kept : found_matches.all;
  result.matched_points = matches.size();
  if (matches.size() < 3) return result;
  FeatureRansacOptions ransac;
  ransac.inlier_distance_mm = options.inlier_distance * v;
  ransac.similarity = options.similarity;
  ransac.max_iterations = options.max_iterations;
  ransac.confidence = options.confidence;
  ransac.seed = options.seed;
  ransac.hypotheses = options.hypotheses;
  const FeatureRansacResult found = feature_ransac(as_vectors(s.points), as_vectors(r.points), matches, ransac);
  result.iterations = found.iterations;
  result.match_share = found.match_share;
  for (const RansacPose& pose : found.poses) {
    FpfhHypothesis h;
    // T_ref_scan = shift(ref_origin) * T_local * shift(-scan_origin).
    h.T_ref_scan = Eigen::Translation3d(ref_origin) * pose.T_ref_scan * Eigen::Translation3d(-scan_origin);
    h.inlier_fraction = pose.inlier_share;
    h.found = pose.inlier_share >= options.min_inlier_fraction;
    result.hypotheses.push_back(h);
  }
  if (!result.hypotheses.empty()) {
    result.found = result.hypotheses.front().found;
    result.inlier_fraction = result.hypotheses.front().inlier_fraction;
    result.T_ref_scan = result.hypotheses.front().T_ref_scan;
  }
  return result;
}

}  // namespace conform
