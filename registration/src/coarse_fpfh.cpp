// PCL's RANSAC templates, instantiated here, make GCC 12 report -Warray-bounds false positives inside Eigen's SSE
// loads of 3-float vectors (Umeyama in TransformationEstimationSVD). The warning is located in the intrinsics
// header, so the pragma must cover its first inclusion, before any other include.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include "conform/registration/coarse_fpfh.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <utility>

#include <pcl/features/fpfh_omp.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/registration/sample_consensus_prerejective.h>
#include <pcl/search/kdtree.h>

#include "conform/core/cloud.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/normals.h"
#include "conform/registration/downsample.h"
#pragma GCC diagnostic pop

namespace conform {

namespace {

using Points = pcl::PointCloud<pcl::PointXYZ>;
using Features = pcl::PointCloud<pcl::FPFHSignature33>;

constexpr std::size_t kMinPoints = 10;
constexpr int kNormalNeighbours = 16;

struct Described {
  Points::Ptr points{new Points};
  Features::Ptr features{new Features};
};

// Downsampled points, relative to `origin` so that float keeps their precision, with their FPFH descriptors.
// The points whose mean distance to their `k` nearest neighbours is within `sigmas` standard deviations of the mean
// over all points (PCL's StatisticalOutlierRemoval): stray returns off the surface, each alone in its voxel, would
// otherwise be as many downsampled points as the surface has and scramble its normals and histograms.
std::vector<Eigen::Vector3d> without_outliers(const std::vector<Eigen::Vector3d>& input, const Eigen::Vector3d& origin,
                                              int k, double sigmas) {
  if (k <= 0 || input.size() <= static_cast<std::size_t>(k)) return input;
  Points::Ptr cloud(new Points);
  for (const Eigen::Vector3d& p : input) {
    const Eigen::Vector3f q = (p - origin).cast<float>();
    cloud->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
  }
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> filter;
  filter.setInputCloud(cloud);
  filter.setMeanK(k);
  filter.setStddevMulThresh(sigmas);
  pcl::Indices kept;
  filter.filter(kept);
  std::vector<Eigen::Vector3d> out;
  out.reserve(kept.size());
  for (const auto i : kept) out.push_back(input[static_cast<std::size_t>(i)]);
  return out;
}

Described describe(const std::vector<Eigen::Vector3d>& input, const Eigen::Vector3d& origin, double voxel_mm,
                   double radius_mm, const FpfhOptions& options, const char* what) {
  const std::vector<Eigen::Vector3d> down =
      voxel_downsample(without_outliers(input, origin, options.outlier_neighbours, options.outlier_sigmas), voxel_mm);
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
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>(estimate_normals(cloud, normal_options)));
  // Away from the centroid rather than towards it: the same rule on both sides keeps the histograms comparable.
  for (pcl::Normal& n : *normals) n.getNormalVector3fMap() *= -1.0f;

  Described d;
  *d.points = cloud.points;
  pcl::FPFHEstimationOMP<pcl::PointXYZ, pcl::Normal, pcl::FPFHSignature33> fpfh;
  fpfh.setInputCloud(d.points);
  fpfh.setInputNormals(normals);
  fpfh.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
  fpfh.setRadiusSearch(radius_mm);
  fpfh.compute(*d.features);
  return d;
}

// At most `count` of the described points (and their features), at even steps.
Described strided(const Described& all, std::size_t count) {
  const std::size_t n = all.points->size();
  if (n <= count) return all;
  Described out;
  for (std::size_t k = 0; k < count; ++k) {
    out.points->push_back((*all.points)[k * n / count]);
    out.features->push_back((*all.features)[k * n / count]);
  }
  return out;
}

// The scan points whose feature match passes the filters: mutual (the reference feature nearest to the scan's has
// that scan feature as its own nearest) and the ratio test (nearest over second-nearest feature distance below
// `ratio`, Lowe 2004). All of them when fewer than `minimum` pass (the filters are a help, not a condition).
Described matched(const Described& s, const Described& r, bool mutual, double ratio, std::size_t minimum) {
  if (!mutual && ratio <= 0.0) return s;
  pcl::KdTreeFLANN<pcl::FPFHSignature33> in_reference, in_scan;
  in_reference.setInputCloud(r.features);
  if (mutual) in_scan.setInputCloud(s.features);
  Described out;
  std::vector<int> index(2), back(1);
  std::vector<float> distance(2), back_distance(1);
  for (std::size_t i = 0; i < s.points->size(); ++i) {
    const pcl::FPFHSignature33& f = (*s.features)[i];
    if (!std::isfinite(f.histogram[0])) continue;
    if (in_reference.nearestKSearch(f, 2, index, distance) < 2) continue;
    if (ratio > 0.0 && !(std::sqrt(distance[0]) < ratio * std::sqrt(distance[1]))) continue;
    if (mutual && (in_scan.nearestKSearch((*r.features)[static_cast<std::size_t>(index[0])], 1, back,
                                          back_distance) < 1 ||
                   back[0] != static_cast<int>(i))) {
      continue;
    }
    out.points->push_back((*s.points)[i]);
    out.features->push_back(f);
  }
  return out.points->size() >= minimum ? out : s;
}

// From the data: 1/30 of the reference's extent, but at least twice either side's point spacing, so that a voxel
// holds a point and the feature radius (5 voxels) holds enough neighbours for a histogram on a sparse scan.
double auto_voxel(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& reference) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : reference) box.extend(p);
  return std::max({box.diagonal().norm() / 30.0, 2.0 * median_spacing(scan, KdTree(scan)),
                   2.0 * median_spacing(reference, KdTree(reference))});
}

// One RANSAC run, seeded; the pose in the local (origin-shifted) frames.
FpfhHypothesis ransac_once(const Described& sample, const Described& r, const FpfhOptions& options,
                           std::uint64_t seed, double v) {
  pcl::SampleConsensusPrerejective<pcl::PointXYZ, pcl::PointXYZ, pcl::FPFHSignature33> ransac;
  ransac.setInputSource(sample.points);
  ransac.setSourceFeatures(sample.features);
  ransac.setInputTarget(r.points);
  ransac.setTargetFeatures(r.features);
  ransac.setMaximumIterations(options.max_iterations);
  ransac.setNumberOfSamples(3);
  ransac.setCorrespondenceRandomness(options.correspondence_randomness);
  ransac.setSimilarityThreshold(static_cast<float>(options.similarity));
  ransac.setMaxCorrespondenceDistance(options.inlier_distance * v);
  ransac.setInlierFraction(static_cast<float>(options.min_inlier_fraction));
  std::srand(static_cast<unsigned>(seed ^ (seed >> 32)));
  Points aligned;
  ransac.align(aligned);
  FpfhHypothesis h;
  h.seed = seed;
  h.found = ransac.hasConverged();
  h.inlier_fraction = static_cast<double>(ransac.getInliers().size()) / static_cast<double>(sample.points->size());
  const Eigen::Matrix4d local = ransac.getFinalTransformation().cast<double>();
  h.T_ref_scan.linear() = Eigen::Quaterniond(local.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  h.T_ref_scan.translation() = local.topRightCorner<3, 1>();
  return h;
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
  } else if (ransac_points < 3) {
    why = "ransac_points must be >= 3";
  } else if (runs < 1) {
    why = "runs must be >= 1";
  } else if (max_iterations < 1) {
    why = "max_iterations must be >= 1";
  } else if (correspondence_randomness < 1) {
    why = "correspondence_randomness must be >= 1";
  } else if (!(ratio >= 0.0 && ratio <= 1.0)) {
    why = "ratio must be in [0, 1] (0: no ratio test)";
  } else if (outlier_neighbours < 0 || !(outlier_sigmas > 0.0) || !std::isfinite(outlier_sigmas)) {
    why = "outlier_neighbours must be >= 0 (0: no outlier removal) and outlier_sigmas finite and > 0";
  } else if (min_matched_points < 3) {
    why = "min_matched_points must be >= 3";
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
  result.voxel_mm = options.voxel_mm > 0.0 ? options.voxel_mm : auto_voxel(scan, reference);
  const double v = result.voxel_mm;
  // Each side relative to its own first point: PCL computes in float.
  const Eigen::Vector3d scan_origin = scan.front(), ref_origin = reference.front();
  const Described s = describe(scan, scan_origin, v, options.feature_radius * v, options, "scan");
  const Described r = describe(reference, ref_origin, v, options.feature_radius * v, options, "reference");
  result.scan_points = s.points->size();
  result.reference_points = r.points->size();

  const Described sample =
      strided(matched(s, r, options.mutual, options.ratio, options.min_matched_points), options.ransac_points);
  result.matched_points = sample.points->size();
  for (int run = 0; run < options.runs; ++run) {
    const std::uint64_t seed = options.seed + static_cast<std::uint64_t>(run);
    FpfhHypothesis h = ransac_once(sample, r, options, seed, v);
    // T_ref_scan = shift(ref_origin) * T_local * shift(-scan_origin).
    h.T_ref_scan = Eigen::Translation3d(ref_origin) * h.T_ref_scan * Eigen::Translation3d(-scan_origin);
    const bool best = h.found && (!result.found || h.inlier_fraction > result.inlier_fraction);
    if (best || (run == 0 && !h.found)) {
      result.found = h.found;
      result.inlier_fraction = h.inlier_fraction;
      result.T_ref_scan = h.T_ref_scan;
    }
    result.hypotheses.push_back(h);
  }
  return result;
}

}  // namespace conform
