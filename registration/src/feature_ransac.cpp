#include "conform/registration/feature_ransac.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "conform/core/error.h"
#include "conform/core/geometry.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/random.h"
#include "conform/registration/horn.h"

namespace conform {

namespace {

// Samples per block (one generator each) and blocks per round (the early stop is decided between rounds): both
// fixed, so that neither the samples drawn nor the stopping point depend on the number of threads.
constexpr int kBlock = 512;
constexpr int kRoundBlocks = 8;
constexpr int kLocalRounds = 3;  // closed-form refits of each kept pose from its consistent correspondences

struct Frame {
  std::vector<Eigen::Vector3d> scan, reference;  // relative to their own centroids: the tree searches in float
  Eigen::Vector3d scan_centre = Eigen::Vector3d::Zero(), reference_centre = Eigen::Vector3d::Zero();
};

std::vector<Eigen::Vector3d> shifted(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& by) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(p - by);
  return out;
}

bool better(const RansacPose& a, const RansacPose& b) {
  if (a.inliers != b.inliers) return a.inliers > b.inliers;
  return a.rms_mm < b.rms_mm;
}

double angle_between(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd((a.linear() * b.linear().transpose()).eval()).angle();
}

// Keeps the best `n` poses, best first, each more than far_rad or far_mm (at the scan's centre, the origin of the
// local frame) from every better one.
void keep(std::vector<RansacPose>& kept, const RansacPose& pose, int n, double far_rad, double far_mm) {
  const auto close = [&](const RansacPose& k) {
    return angle_between(k.T_ref_scan, pose.T_ref_scan) <= far_rad &&
           (k.T_ref_scan.translation() - pose.T_ref_scan.translation()).norm() <= far_mm;
  };
  for (const RansacPose& k : kept) {
    if (close(k) && !better(pose, k)) return;
  }
  kept.erase(std::remove_if(kept.begin(), kept.end(), close), kept.end());
  kept.insert(std::upper_bound(kept.begin(), kept.end(), pose, better), pose);
  if (kept.size() > static_cast<std::size_t>(n)) kept.resize(static_cast<std::size_t>(n));
}

struct Context {
  const Frame& frame;
  const std::vector<std::pair<int, int>>& matches;
  const FeatureRansacOptions& options;
  const std::vector<Eigen::Vector3d>& scored;  // the scan points a pose is scored on
  const KdTree& tree;                          // over frame.reference
  double far_rad, far_mm;
};

RansacPose score(const Context& c, const Eigen::Isometry3d& T) {
  const double d2 = c.options.inlier_distance_mm * c.options.inlier_distance_mm;
  RansacPose pose;
  pose.T_ref_scan = T;
  double sum = 0.0;
  for (const Eigen::Vector3d& p : c.scored) {
    float sq = 0.0f;
    if (c.tree.nearest((T * p).cast<float>(), &sq) < 0 || !(static_cast<double>(sq) <= d2)) continue;
    ++pose.inliers;
    sum += static_cast<double>(sq);
  }
  pose.inlier_share = static_cast<double>(pose.inliers) / static_cast<double>(c.scored.size());
  pose.rms_mm = pose.inliers > 0 ? std::sqrt(sum / static_cast<double>(pose.inliers)) : 0.0;
  return pose;
}

// The pose of three correspondences, or false when the pre-rejection turns them down.
bool sample_pose(const Context& c, const int (&pick)[3], Eigen::Isometry3d* T) {
  std::vector<Eigen::Vector3d> s(3), r(3);
  for (int k = 0; k < 3; ++k) {
    const auto& m = c.matches[static_cast<std::size_t>(pick[k])];
    s[static_cast<std::size_t>(k)] = c.frame.scan[static_cast<std::size_t>(m.first)];
    r[static_cast<std::size_t>(k)] = c.frame.reference[static_cast<std::size_t>(m.second)];
  }
  const double shortest = c.options.min_edge * c.options.inlier_distance_mm;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t j = (i + 1) % 3;
    const double ds = (s[i] - s[j]).norm(), dr = (r[i] - r[j]).norm();
    if (ds < shortest || ds < c.options.similarity * dr || dr < c.options.similarity * ds) return false;
  }
  const HornResult h = horn_transform(s, r);
  if (!h.well_posed) return false;
  for (std::size_t k = 0; k < 3; ++k) {
    if ((h.T_ref_scan * s[k] - r[k]).norm() > c.options.inlier_distance_mm) return false;
  }
  *T = h.T_ref_scan;
  return true;
}

struct BlockResult {
  std::vector<RansacPose> kept;
  int drawn = 0, scored = 0;
};

BlockResult run_block(const Context& c, std::uint64_t block, int count) {
  // One stream per block, from the seed and the block's index: the same draws whatever the thread count.
  Random random(c.options.seed, block);
  BlockResult out;
  const std::uint64_t n = c.matches.size();
  for (int i = 0; i < count; ++i) {
    ++out.drawn;
    int pick[3];
    pick[0] = static_cast<int>(random.below(n));
    do pick[1] = static_cast<int>(random.below(n));
    while (pick[1] == pick[0]);
    do pick[2] = static_cast<int>(random.below(n));
    while (pick[2] == pick[0] || pick[2] == pick[1]);
    Eigen::Isometry3d T;
    if (!sample_pose(c, pick, &T)) continue;
    ++out.scored;
    keep(out.kept, score(c, T), c.options.hypotheses, c.far_rad, c.far_mm);
  }
  return out;
}

// The share of the correspondences that the pose maps within the inlier distance.
double match_share(const Context& c, const Eigen::Isometry3d& T) {
  std::size_t n = 0;
  for (const auto& m : c.matches) {
    const Eigen::Vector3d s = T * c.frame.scan[static_cast<std::size_t>(m.first)];
    n += (s - c.frame.reference[static_cast<std::size_t>(m.second)]).norm() <= c.options.inlier_distance_mm;
  }
  return static_cast<double>(n) / static_cast<double>(c.matches.size());
}

// Local optimisation (Chum, Matas & Kittler 2003, LO-RANSAC): the pose re-estimated in closed form from every
// correspondence it maps within the inlier distance, a few times over. Three sampled pairs fix a pose only as well as
// their own noise allows; all the consistent ones fix it as well as the features do (on a height field they, not the
// flat surface, fix the in-plane motion). Kept when it scores at least as well.
RansacPose locally_optimised(const Context& c, const RansacPose& pose) {
  RansacPose best = pose;
  for (int round = 0; round < kLocalRounds; ++round) {
    std::vector<Eigen::Vector3d> s, r;
    for (const auto& m : c.matches) {
      const Eigen::Vector3d& p = c.frame.scan[static_cast<std::size_t>(m.first)];
      const Eigen::Vector3d& q = c.frame.reference[static_cast<std::size_t>(m.second)];
      if ((best.T_ref_scan * p - q).norm() > c.options.inlier_distance_mm) continue;
      s.push_back(p);
      r.push_back(q);
    }
    if (s.size() < 3) break;
    const HornResult h = horn_transform(s, r);
    if (!h.well_posed) break;
    const RansacPose next = score(c, h.T_ref_scan);
    if (better(best, next)) break;
    best = next;
  }
  return best;
}

// Samples needed for an all-inlier draw with the given confidence when a share w of the correspondences is right.
double samples_needed(double w, double confidence) {
  if (confidence >= 1.0) return std::numeric_limits<double>::infinity();
  const double all = w * w * w;
  if (all <= 0.0) return std::numeric_limits<double>::infinity();
  if (all >= 1.0) return 1.0;
  return std::log(1.0 - confidence) / std::log(1.0 - all);
}

}  // namespace

bool FeatureRansacOptions::IsValid(std::string* error) const {
  std::string why;
  if (!(inlier_distance_mm > 0.0) || !std::isfinite(inlier_distance_mm)) {
    why = "inlier_distance_mm must be finite and > 0";
  } else if (!(similarity >= 0.0 && similarity < 1.0)) {
    why = "similarity must be in [0, 1)";
  } else if (!(min_edge >= 0.0) || !std::isfinite(min_edge)) {
    why = "min_edge must be finite and >= 0";
  } else if (max_iterations < 1) {
    why = "max_iterations must be >= 1";
  } else if (!(confidence > 0.0 && confidence <= 1.0)) {
    why = "confidence must be in (0, 1]";
  } else if (hypotheses < 1) {
    why = "hypotheses must be >= 1";
  } else if (!(distinct_deg >= 0.0) || !std::isfinite(distinct_deg) || !(distinct_mm >= 0.0) ||
             !std::isfinite(distinct_mm)) {
    why = "distinct_deg and distinct_mm must be finite and >= 0";
  } else if (score_points < 3) {
    why = "score_points must be >= 3";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

FeatureRansacResult feature_ransac(const std::vector<Eigen::Vector3d>& scan,
                                   const std::vector<Eigen::Vector3d>& reference,
                                   const std::vector<std::pair<int, int>>& matches,
                                   const FeatureRansacOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("feature RANSAC options: " + why);
  if (matches.size() < 3) {
    throw Error("feature RANSAC: " + std::to_string(matches.size()) + " correspondences; at least 3 are needed");
  }
  for (const auto& m : matches) {
    if (m.first < 0 || static_cast<std::size_t>(m.first) >= scan.size() || m.second < 0 ||
        static_cast<std::size_t>(m.second) >= reference.size()) {
      throw Error("feature RANSAC: correspondence (" + std::to_string(m.first) + ", " + std::to_string(m.second) +
                  ") is out of range of " + std::to_string(scan.size()) + " scan and " +
                  std::to_string(reference.size()) + " reference points");
    }
  }
  Frame frame;
  frame.scan_centre = centroid(scan);
  frame.reference_centre = centroid(reference);
  frame.scan = shifted(scan, frame.scan_centre);
  frame.reference = shifted(reference, frame.reference_centre);
  std::vector<Eigen::Vector3d> scored;
  const std::size_t n = std::min(frame.scan.size(), options.score_points);
  for (std::size_t k = 0; k < n; ++k) scored.push_back(frame.scan[k * frame.scan.size() / n]);
  const KdTree tree(frame.reference);
  const Context c{frame,
                  matches,
                  options,
                  scored,
                  tree,
                  options.distinct_deg * M_PI / 180.0,
                  options.distinct_mm > 0.0 ? options.distinct_mm : 5.0 * options.inlier_distance_mm};

  FeatureRansacResult result;
  std::vector<RansacPose> kept;
  for (int first = 0; first < options.max_iterations; first += kBlock * kRoundBlocks) {
    std::vector<BlockResult> blocks(kRoundBlocks);
#pragma omp parallel for schedule(dynamic, 1)
    for (int b = 0; b < kRoundBlocks; ++b) {
      const int begin = first + b * kBlock;
      const int count = std::min(kBlock, options.max_iterations - begin);
      if (count > 0) blocks[static_cast<std::size_t>(b)] = run_block(c, static_cast<std::uint64_t>(begin / kBlock), count);
    }
    for (const BlockResult& b : blocks) {
      result.iterations += b.drawn;
      result.scored += b.scored;
      for (const RansacPose& p : b.kept) keep(kept, p, options.hypotheses, c.far_rad, c.far_mm);
    }
    if (kept.empty()) continue;
    result.match_share = match_share(c, kept.front().T_ref_scan);
    if (result.iterations < options.max_iterations &&
        static_cast<double>(result.iterations) >= samples_needed(result.match_share, options.confidence)) {
      result.stopped_early = true;
      break;
    }
  }
  std::vector<RansacPose> optimised;
  for (const RansacPose& p : kept) keep(optimised, locally_optimised(c, p), options.hypotheses, c.far_rad, c.far_mm);
  kept = std::move(optimised);
  // Back from the centroid frames: T = shift(reference centre) * T_local * shift(-scan centre).
  for (RansacPose& p : kept) {
    p.T_ref_scan = Eigen::Translation3d(frame.reference_centre) * p.T_ref_scan * Eigen::Translation3d(-frame.scan_centre);
  }
  result.poses = std::move(kept);
  return result;
}

}  // namespace conform
