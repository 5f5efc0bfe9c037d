#pragma once
// Coarse alignment from local shape: both clouds cleared of stray points (statistical outlier removal) and
// voxel-downsampled, PCA normals (turned away from each cloud's
// centroid), Fast Point Feature Histograms (Rusu et al. 2009, PCL's FPFHEstimationOMP), and RANSAC over feature
// matches with pre-rejection of inconsistent samples (Buch et al. 2013, PCL's SampleConsensusPrerejective).
// Unlike PCA it works for partial overlap, as long as the overlap has distinctive shape.
//
// PCL's RANSAC draws from std::rand(): fpfh_ransac seeds it (std::srand) with options.seed before it runs, so the
// result is reproducible, but calling it changes the global rand() state and it must not run concurrently with
// other users of std::rand().

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct FpfhOptions {
  double voxel_mm = 0.0;  // downsampling voxel; 0: the reference's bounding-box diagonal / 30, >= 2 point spacings
  double feature_radius = 5.0;        // FPFH support radius, in voxels
  double inlier_distance = 1.5;       // a RANSAC inlier is within this many voxels of the reference
  double min_inlier_fraction = 0.25;  // of the RANSAC scan points, for a hypothesis to count
  int max_iterations = 3000;          // RANSAC hypotheses
  // RANSAC samples from, and scores each hypothesis on, at most this many of the downsampled scan points (evenly
  // strided; every reference point stays a candidate match): a hypothesis costs one nearest-neighbour search per
  // point, and a few hundred points judge a coarse pose as well as thousands.
  std::size_t ransac_points = 400;
  int correspondence_randomness = 3;  // a sample's match is drawn from its this many nearest features
  double similarity = 0.9;            // pre-rejection: edge-length ratio of sample and match polygons, in [0, 1)
  // Before downsampling, points whose mean distance to their outlier_neighbours nearest is more than outlier_sigmas
  // standard deviations above the mean are dropped (stray returns); 0 neighbours: none dropped.
  int outlier_neighbours = 16;
  double outlier_sigmas = 2.0;
  // Match filters on the scan points RANSAC draws from: mutual nearest features, and the ratio test (nearest over
  // second-nearest feature distance below `ratio`; 0: none). Ignored when fewer than min_matched_points pass.
  bool mutual = false;
  double ratio = 0.0;
  std::size_t min_matched_points = 50;
  std::uint64_t seed = 1;
  // RANSAC runs over the same descriptors, seeded seed, seed + 1, ...: each run's answer is a hypothesis of its own
  // (hypotheses), so that one unlucky run (a mirror pose on a near-symmetric part) meets competition.
  int runs = 4;

  bool IsValid(std::string* error) const;
};

struct FpfhHypothesis {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  bool found = false;
  double inlier_fraction = 0.0;
  std::uint64_t seed = 0;
};

struct FpfhResult {
  std::vector<FpfhHypothesis> hypotheses;  // one per run, in seed order; the fields below are the best found one's
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  bool found = false;            // a hypothesis reached min_inlier_fraction
  double inlier_fraction = 0.0;  // of the RANSAC scan points, within inlier_distance
  double voxel_mm = 0.0;         // used
  std::size_t scan_points = 0;   // after downsampling
  std::size_t matched_points = 0;  // RANSAC drew from (after the match filters and ransac_points)
  std::size_t reference_points = 0;
};

// Throws conform::Error for invalid options or fewer than 10 points on either side after downsampling.
FpfhResult fpfh_ransac(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& reference,
                       const FpfhOptions& options);

}  // namespace conform
