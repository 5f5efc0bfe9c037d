#pragma once
// Coarse alignment from local shape: both clouds cleared of stray points (statistical outlier removal) and
// voxel-downsampled at a voxel from the data, PCA normals (turned away from each cloud's
// centroid), Fast Point Feature Histograms (Rusu et al. 2009, PCL's FPFHEstimationOMP), mutual nearest-feature
// correspondences, and RANSAC over them with pre-rejection of inconsistent samples (feature_ransac.h).
// Unlike PCA it works for partial overlap, as long as the overlap has distinctive shape.
//
// RANSAC is conform's own (feature_ransac.h): seeded, parallel, the same result for any number of threads.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct FpfhOptions {
  // Downsampling voxel; 0: automatic, the side with less surface left with about target_points points (at least 2
  // point spacings on both sides).
  double voxel_mm = 0.0;
  std::size_t target_points = 2000;
  double feature_radius = 5.0;  // FPFH support radius, in voxels
  // When fewer than min_matched_points correspondences pass the match filters at feature_radius, the features are
  // computed again at this radius (voxels) and the set with more passing is used: a support wider than the part's
  // walls sees their far faces in the reference but not in a scan from one side. 0: never.
  double narrow_feature_radius = 2.5;
  double inlier_distance = 1.5;       // a RANSAC inlier is within this many voxels of the reference
  double min_inlier_fraction = 0.25;  // of the downsampled scan points, for a hypothesis to count
  int max_iterations = 100000;        // RANSAC samples at most (feature_ransac.h; it stops early at `confidence`)
  double confidence = 0.999;
  double similarity = 0.9;  // pre-rejection: edge-length ratio of sample and match triangles, in [0, 1)
  // Before downsampling (on a voxel grid a third of voxel_mm), points whose mean distance to their
  // outlier_neighbours nearest is more than outlier_sigmas standard deviations above the mean are dropped (stray
  // returns); 0 neighbours: none dropped.
  int outlier_neighbours = 16;
  double outlier_sigmas = 2.0;
  // Match filters on the correspondences RANSAC draws from (each downsampled scan point and the reference point of
  // the nearest feature): mutual nearest features, and the ratio test (nearest over second-nearest feature distance
  // below `ratio`; 0: none). Ignored when fewer than min_matched_points pass.
  bool mutual = true;
  double ratio = 0.0;
  std::size_t min_matched_points = 50;
  std::uint64_t seed = 1;
  // The best this many distinct RANSAC poses are hypotheses (more than 1 degree or 5 inlier distances apart): their
  // short ICPs (multi_start.h) pick the one that fits, and a mirror pose on a near-symmetric part meets competition.
  int hypotheses = 6;

  bool IsValid(std::string* error) const;
};

struct FpfhHypothesis {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  bool found = false;            // reached min_inlier_fraction
  double inlier_fraction = 0.0;  // of the downsampled scan points, within inlier_distance of a reference point
};

struct FpfhResult {
  std::vector<FpfhHypothesis> hypotheses;  // best first; the fields below are the best's
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  bool found = false;               // a hypothesis reached min_inlier_fraction
  double inlier_fraction = 0.0;     // of the downsampled scan points, within inlier_distance
  double voxel_mm = 0.0;            // used
  std::size_t scan_points = 0;      // after downsampling
  std::size_t matched_points = 0;   // correspondences RANSAC drew from (after the match filters)
  std::size_t filtered_points = 0;  // correspondences that passed the match filters
  double feature_radius_mm = 0.0;   // the FPFH support radius used
  std::size_t reference_points = 0;
  int iterations = 0;        // RANSAC samples drawn
  double match_share = 0.0;  // of the correspondences, consistent with the best pose
};

// Throws conform::Error for invalid options or fewer than 10 points on either side after downsampling.
FpfhResult fpfh_ransac(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& reference,
                       const FpfhOptions& options);

}  // namespace conform
