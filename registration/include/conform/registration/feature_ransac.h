#pragma once
// RANSAC over feature correspondences (Fischler & Bolles 1981), the hypothesis stage of global registration: three
// correspondences give a pose in closed form (Horn 1987); a sample is rejected before it is scored when the edges of
// its two triangles differ in length (their ratio below `similarity`, Buch et al. 2013's pre-rejection) or when a
// sampled scan point lands farther than the inlier distance from its matched reference point; a surviving pose is
// scored by how many scan points land within the inlier distance of a reference point.
//
// Deterministic and parallel: the iterations run in blocks of a fixed size, each block with its own generator seeded
// from (seed, block index), and the blocks' results are merged in block order, so the answer does not depend on the
// number of threads. It stops early, at the end of a round of blocks, once the best pose explains enough of the
// correspondences that a better sample is unlikely to be drawn (the confidence rule of RANSAC: k = log(1 - p) /
// log(1 - w^3), w the share of correspondences consistent with the best pose).

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace conform {

struct FeatureRansacOptions {
  double inlier_distance_mm = 1.0;  // a scan point within this of a reference point is an inlier
  double similarity = 0.9;          // pre-rejection: shorter over longer edge of sample and match, in [0, 1)
  // Samples whose shortest scan edge is below this many inlier distances are skipped: three nearly coincident points
  // fix no rotation.
  double min_edge = 2.0;
  int max_iterations = 100000;  // samples drawn at most
  double confidence = 0.999;    // of having drawn an all-inlier sample, for the early stop; 1: never stop early
  std::uint64_t seed = 1;
  // The best this many distinct poses are kept (a pose is distinct when it is more than distinct_deg, or moves the
  // scan's centre more than distinct_mm, away from every better one; 0 mm: 5 inlier distances). Each is refitted in
  // closed form to every correspondence it explains (LO-RANSAC, Chum et al. 2003) before it is returned.
  int hypotheses = 6;
  double distinct_deg = 1.0;
  double distinct_mm = 0.0;
  // Scan points each surviving pose is scored on (evenly strided; all when fewer).
  std::size_t score_points = 2000;

  bool IsValid(std::string* error) const;
};

struct RansacPose {
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  std::size_t inliers = 0;    // of the scored scan points, within the inlier distance
  double inlier_share = 0.0;  // inliers over the scored scan points
  double rms_mm = 0.0;        // of the inliers' distances
};

struct FeatureRansacResult {
  std::vector<RansacPose> poses;  // the best first (more inliers, then lower RMS); empty when no sample was scored
  int iterations = 0;             // samples drawn
  int scored = 0;                 // samples that passed the pre-rejection and were scored
  double match_share = 0.0;       // of the correspondences, consistent with the best pose
  bool stopped_early = false;     // by the confidence rule, before max_iterations
};

// matches: (scan index, reference index) pairs. Throws conform::Error for invalid options, an index out of range, or
// fewer than 3 matches.
FeatureRansacResult feature_ransac(const std::vector<Eigen::Vector3d>& scan,
                                   const std::vector<Eigen::Vector3d>& reference,
                                   const std::vector<std::pair<int, int>>& matches,
                                   const FeatureRansacOptions& options);

}  // namespace conform
