#include "pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "conform/core/radix_sort.h"
#include "conform/core/z_order.h"

namespace conform::detail {

namespace {

// A parallel loop costs a team's start and a barrier, and libgomp's idle threads spin afterwards; below this many
// points one thread is faster, and on a loaded machine much faster.
constexpr std::ptrdiff_t kSerialBelow = 16384;
constexpr int kChunk = 512;

// Nearest reference point: the tree searches in float, the distance is then taken in double. The point and its
// normal are read in the tree's order (IcpReference::by_position), near the last query's.
void nearest_point(const IcpReference& reference, const Eigen::Vector3d& q, double max_distance_mm, Pair& pair,
                   PairCache* cache, std::size_t i) {
  const Eigen::Vector3f qf = q.cast<float>();
  if (!qf.allFinite()) return;  // beyond float range: nothing of the reference can be near
  const IcpReference::Sample* s = nullptr;
  if (cache != nullptr) {
    s = cache->nearest(reference, i, qf);
  } else {
    const int j = reference.tree().nearest_position(qf);
    if (j >= 0) s = &reference.by_position()[static_cast<std::size_t>(j)];
  }
  if (s == nullptr) return;
  pair.target = s->point;
  pair.normal = s->normal;
  pair.distance = (q - pair.target).norm();
  pair.found = pair.distance <= max_distance_mm;
}

// The closest point on the flat triangles moved onto the smooth surface the vertices and their normals describe
// (core/phong_surface.h: Phong tessellation, creases kept sharp): the flat facets are off by their chord error
// (kappa h^2 / 8 at an edge's middle: 0.013 mm on a 4 mm mesh of a 150 mm radius), an error that is systematic and
// biases the pose.
void nearest_surface_point(const IcpReference& reference, const Eigen::Vector3d& q, double max_distance_mm,
                           Pair& pair, PairCache* cache, std::size_t i) {
  const SurfacePoint s = cache != nullptr ? cache->closest(reference.surface(), i, q, max_distance_mm)
                                          : reference.surface().closest(q, max_distance_mm);
  if (!s.found()) return;
  const PhongPoint smooth = reference.phong().lift(s);
  pair.target = smooth.point;
  // A face without area has no normal of its own: its edges' pseudo-normal.
  pair.normal = smooth.normal.isZero() ? reference.surface().normal_at(s) : smooth.normal;
  pair.distance = (q - pair.target).norm();
  pair.found = pair.distance <= max_distance_mm && pair.normal.allFinite();
}

}  // namespace

std::vector<Eigen::Vector3d> spatially_ordered(const std::vector<Eigen::Vector3d>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (std::size_t i : z_order(points)) out.push_back(points[i]);
  return out;
}

void find_pairs(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& scan_normals,
                const Eigen::Isometry3d& T_ref_scan, const IcpReference& reference, const PairRules& rules,
                std::vector<Pair>& pairs, PairCache* cache) {
  const bool with_normals = scan_normals.size() == scan.size();
  const IcpMethod method = rules.method;
  const double max_distance_mm = rules.max_distance_mm;
  pairs.resize(scan.size());
  const auto n = static_cast<std::ptrdiff_t>(scan.size());
#pragma omp parallel for schedule(dynamic, kChunk) if (n > kSerialBelow)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    Pair& pair = pairs[static_cast<std::size_t>(i)];
    pair = Pair{};
    pair.q = T_ref_scan * scan[static_cast<std::size_t>(i)];
    if (!pair.q.allFinite()) continue;  // overflow: nothing to pair it with (and the searches would throw)
    if (method == IcpMethod::kPointToSurface) {
      nearest_surface_point(reference, pair.q, max_distance_mm, pair, cache, static_cast<std::size_t>(i));
    } else {
      nearest_point(reference, pair.q, max_distance_mm, pair, cache, static_cast<std::size_t>(i));
    }
    if (!pair.found) continue;
    if (with_normals) pair.scan_normal = T_ref_scan.linear() * scan_normals[static_cast<std::size_t>(i)];
    pair.residual = method == IcpMethod::kPointToPoint ? pair.distance : pair.normal.dot(pair.q - pair.target);
  }
}

std::vector<std::size_t> select_inliers(const std::vector<Pair>& pairs, double overlap) {
  // Chetverikov et al. 2002: keep the ceil(overlap N) smallest distances of the N scan points.
  const auto keep = static_cast<std::size_t>(std::ceil(overlap * static_cast<double>(pairs.size())));
  if (keep == 0) return {};
  std::vector<std::size_t> inliers;
  if (keep >= pairs.size()) {  // no trimming: every pair found
    inliers.reserve(pairs.size());
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      if (pairs[i].found) inliers.push_back(i);
    }
    return inliers;
  }
  std::vector<double> distances;
  distances.reserve(pairs.size());
  for (const Pair& p : pairs) {
    if (p.found) distances.push_back(p.distance);
  }
  double limit = std::numeric_limits<double>::infinity();
  if (distances.size() > keep) {
    std::nth_element(distances.begin(), distances.begin() + static_cast<std::ptrdiff_t>(keep - 1), distances.end());
    limit = distances[keep - 1];
  }
  inliers.reserve(std::min(keep, distances.size()));
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (pairs[i].found && pairs[i].distance <= limit) inliers.push_back(i);
  }
  return inliers;
}

namespace {
constexpr double kFractionalMinCut = 3.0;
}  // namespace

double fractional_overlap(const std::vector<Pair>& pairs, double min_fraction, double lambda) {
  std::vector<double> squared;
  squared.reserve(pairs.size());
  for (const Pair& p : pairs) {
    if (p.found) squared.push_back(p.distance * p.distance);
  }
  if (squared.empty()) return 0.0;
  radix_sort(squared);  // every step of every fit: linear, not n log n
  const double n = static_cast<double>(pairs.size());
  const auto first = static_cast<std::size_t>(std::max(1.0, std::ceil(min_fraction * n)));
  double sum = 0.0, best_score = std::numeric_limits<double>::infinity();
  std::size_t best = squared.size();
  for (std::size_t k = 1; k <= squared.size(); ++k) {
    sum += squared[k - 1];
    if (k < first) continue;
    const double f = static_cast<double>(k) / n;
    // The floor keeps exact (noise-free) distances from scoring 0 at every f: then the most pairs win.
    const double score = std::sqrt(std::max(sum / static_cast<double>(k), 1e-24)) / std::pow(f, lambda);
    if (score < best_score) {
      best_score = score;
      best = k;
    }
  }
  // Never trim pairs within kFractionalMinCut robust standard deviations of the kept distances: FRMSD alone trims
  // the noise's own tail; pairs off the overlap are many noise widths away.
  const double sigma = 1.4826 * std::sqrt(squared[(best - 1) / 2]);
  const double cut = std::max(std::sqrt(squared[best - 1]), kFractionalMinCut * sigma);
  const auto kept = static_cast<std::size_t>(std::upper_bound(squared.begin(), squared.end(), cut * cut) -
                                             squared.begin());
  return static_cast<double>(std::max(best, kept)) / n;
}

std::vector<double> robust_weights(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers,
                                   RobustKernel kernel, double min_scale_mm, double* scale_mm, double widen_to_mm) {
  std::vector<double> weights(inliers.size(), 1.0);
  *scale_mm = 0.0;
  if (kernel == RobustKernel::kNone || inliers.empty()) return weights;
  *scale_mm = noise_scale(pairs, inliers, min_scale_mm);
  const double scale = std::max(*scale_mm, widen_to_mm);
  const double huber = 1.345 * scale, tukey = 4.685 * scale;
  for (std::size_t k = 0; k < inliers.size(); ++k) {
    const double r = std::abs(pairs[inliers[k]].residual);
    if (kernel == RobustKernel::kHuber) {
      weights[k] = r <= huber ? 1.0 : huber / r;
    } else {
      const double u = r / tukey;
      weights[k] = u < 1.0 ? (1.0 - u * u) * (1.0 - u * u) : 0.0;
    }
  }
  return weights;
}

double noise_scale(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers, double min_scale_mm,
                   bool along_normal) {
  if (inliers.empty()) return 0.0;
  std::vector<double> magnitudes(inliers.size());
  for (std::size_t k = 0; k < inliers.size(); ++k) {
    const Pair& p = pairs[inliers[k]];
    magnitudes[k] = std::abs(along_normal ? p.normal.dot(p.q - p.target) : p.residual);
  }
  const auto middle = magnitudes.begin() + static_cast<std::ptrdiff_t>(magnitudes.size() / 2);
  std::nth_element(magnitudes.begin(), middle, magnitudes.end());
  return std::max(1.4826 * *middle, min_scale_mm);
}

double inlier_rms(const std::vector<Pair>& pairs, const std::vector<std::size_t>& inliers) {
  if (inliers.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t i : inliers) sum += pairs[i].residual * pairs[i].residual;
  return std::sqrt(sum / static_cast<double>(inliers.size()));
}

}  // namespace conform::detail
