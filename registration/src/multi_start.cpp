#include "conform/registration/multi_start.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include "conform/core/error.h"
#include "conform/registration/downsample.h"

namespace conform {

namespace {

// sqrt(mean(min(d, cap)^2)) over the points, d the distance to the nearest reference point.
double truncated_rms(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                     const IcpReference& reference, double cap) {
  double sum = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = T * p;
    const Eigen::Vector3f qf = q.cast<float>();
    double d = cap;
    if (qf.allFinite()) {
      const int j = reference.tree().nearest(qf);
      if (j >= 0) d = std::min(cap, (q - reference.points()[static_cast<std::size_t>(j)]).norm());
    }
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(points.size()));
}

// Which points lie within `tolerance` of the reference plane at their nearest reference point, that point no farther
// than `reach` (a mesh's vertices are sparse: the plane distance is the one that measures the fit).
std::vector<char> inliers(const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T,
                          const IcpReference& reference, double tolerance, double reach) {
  std::vector<char> inside(points.size(), 0);
  const bool has_normals = reference.normals().size() == reference.points().size();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d q = T * points[i];
    const Eigen::Vector3f qf = q.cast<float>();
    if (!qf.allFinite()) continue;
    const int j = reference.tree().nearest(qf);
    if (j < 0) continue;
    const Eigen::Vector3d d = q - reference.points()[static_cast<std::size_t>(j)];
    const double along = has_normals ? std::abs(d.dot(reference.normals()[static_cast<std::size_t>(j)])) : d.norm();
    inside[i] = along <= tolerance && d.norm() <= reach;
  }
  return inside;
}

double share_of(const std::vector<char>& mask) {
  return static_cast<double>(std::count(mask.begin(), mask.end(), 1)) / static_cast<double>(mask.size());
}

// Whether the best start's inliers outnumber the other's where they disagree, beyond chance: at two poses of a
// symmetric surface the points in only one pose's inlier set are threshold noise, equally likely either way
// (binomial, p = 1/2); a real difference (a boss that only one pose puts on the reference) is one-sided.
bool separated(std::size_t best_only, std::size_t other_only, std::size_t n, const MultiStartOptions& o) {
  if (o.separation_z <= 0.0) return false;
  const double b = static_cast<double>(best_only), a = static_cast<double>(other_only);
  return b >= o.separation_min_share * static_cast<double>(n) && b >= o.separation_ratio * a &&
         b - a > o.separation_z * std::sqrt(a + b);
}

// Higher share first, then lower truncated RMS.
bool better(const StartReport& a, const StartReport& b) {
  if (a.inlier_share != b.inlier_share) return a.inlier_share > b.inlier_share;
  return a.score_mm < b.score_mm;
}

double size_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  return box.diagonal().norm();
}

// The best pose followed by a turn of the reference about its principal axes through its centroid: half turns about
// each axis, and quarter turns about an axis whose two companions spread alike (within `similarity`).
std::vector<CoarseStart> symmetry_starts(const StartReport& best, const std::vector<Eigen::Vector3d>& reference,
                                         double similarity) {
  std::vector<CoarseStart> out;
  if (reference.size() < 3) return out;
  const PrincipalAxes axes = principal_axes(reference);
  const auto add = [&](int k, double degrees) {
    const Eigen::Vector3d a = axes.axes.col(k);
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() = Eigen::AngleAxisd(degrees * M_PI / 180.0, a).toRotationMatrix();
    turn.translation() = axes.centroid - turn.linear() * axes.centroid;
    out.push_back({best.label + " turned " + std::to_string(static_cast<int>(degrees)) + " deg about reference axis " +
                       std::to_string(k + 1),
                   turn * best.T_probe});
  };
  for (int k = 0; k < 3; ++k) {
    add(k, 180.0);
    const double u = axes.variances((k + 1) % 3), v = axes.variances((k + 2) % 3);
    if (std::abs(u - v) <= similarity * std::max(u, v)) {
      add(k, 90.0);
      add(k, -90.0);
    }
  }
  return out;
}

}  // namespace

bool MultiStartOptions::IsValid(std::string* error) const {
  std::string why;
  if (!probe.IsValid(&why)) {
    why = "probe: " + why;
  } else if (!std::isfinite(probe.max_correspondence_distance_mm)) {
    why = "probe.max_correspondence_distance_mm must be finite: it caps the score of a point that found nothing";
  } else if (probe_points < probe.min_correspondences) {
    why = "probe_points must be at least probe.min_correspondences";
  } else if (!(ambiguity >= 0.0) || !std::isfinite(ambiguity)) {
    why = "ambiguity must be finite and >= 0";
  } else if (!(inlier_distance_mm >= 0.0) || !std::isfinite(inlier_distance_mm)) {
    why = "inlier_distance_mm must be finite and >= 0 (0: score by truncated RMS)";
  } else if (!(share_margin >= 0.0 && share_margin < 1.0)) {
    why = "share_margin must be in [0, 1)";
  } else if (!(separation_z >= 0.0) || !std::isfinite(separation_z) || !(separation_ratio >= 1.0) ||
             !std::isfinite(separation_ratio) || !(separation_min_share >= 0.0 && separation_min_share <= 1.0)) {
    why = "separation_z must be finite and >= 0, separation_ratio finite and >= 1, separation_min_share in [0, 1]";
  } else if (!(symmetry_similarity >= 0.0 && symmetry_similarity < 1.0)) {
    why = "symmetry_similarity must be in [0, 1)";
  } else if (!(distinct_deg > 0.0) || !std::isfinite(distinct_deg) || !(distinct_mm >= 0.0) ||
             !std::isfinite(distinct_mm)) {
    why = "distinct_deg must be finite and > 0, distinct_mm finite and >= 0";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

MultiStartResult rank_starts(const std::vector<Eigen::Vector3d>& scan, const IcpReference& reference,
                             const std::vector<CoarseStart>& starts, const MultiStartOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("multi-start options: " + why);
  if (starts.empty()) throw Error("multi-start: no starts given");
  const std::vector<Eigen::Vector3d> subset = stride_downsample(scan, options.probe_points);
  const double cap = options.probe.max_correspondence_distance_mm;
  const bool by_share = options.inlier_distance_mm > 0.0;
  const double reach =
      by_share ? 3.0 * median_spacing(reference.points(), reference.tree()) + options.inlier_distance_mm : 0.0;
  MultiStartResult result;
  std::vector<std::vector<char>> masks;
  const auto probe_start = [&](const CoarseStart& start) {
    IcpOptions probe = options.probe;
    probe.progress = nullptr;
    const IcpResult r = icp(subset, reference, start.T_ref_scan, probe);
    StartReport report;
    report.label = start.label;
    report.T_start = start.T_ref_scan;
    report.T_probe = r.T_ref_scan;
    report.score_mm = truncated_rms(subset, r.T_ref_scan, reference, cap);
    report.inlier_fraction = r.inlier_fraction;
    report.rms_mm = r.rms_mm;
    if (by_share) {
      masks.push_back(inliers(subset, r.T_ref_scan, reference, options.inlier_distance_mm, reach));
      report.inlier_share = share_of(masks.back());
    }
    result.starts.push_back(report);
    if (result.best < 0 || better(report, result.starts[static_cast<std::size_t>(result.best)])) {
      result.best = static_cast<int>(result.starts.size()) - 1;
    }
  };
  for (const CoarseStart& start : starts) probe_start(start);
  if (options.probe_reference_symmetry) {
    // The best pose turned by the reference's own candidate symmetries: if the reference (or the part of it the scan
    // covers) looks the same turned, the turned pose fits as well and the ambiguity test below finds it, whether or
    // not any start happened to land there (a partial scan of a symmetric plate: every FPFH run may agree).
    const StartReport best_given = result.starts[static_cast<std::size_t>(result.best)];
    for (const CoarseStart& turned : symmetry_starts(best_given, reference.points(), options.symmetry_similarity)) {
      probe_start(turned);
    }
  }
  const StartReport best = result.starts[static_cast<std::size_t>(result.best)];
  const Eigen::Vector3d centre =
      std::accumulate(subset.begin(), subset.end(), Eigen::Vector3d(Eigen::Vector3d::Zero())) /
      static_cast<double>(subset.size());
  const double size_mm = size_of(subset);
  const double far_mm = !by_share                  ? 0.01 * size_mm
                        : options.distinct_mm > 0.0 ? options.distinct_mm
                                                    : std::max(10.0 * options.inlier_distance_mm, 0.01 * size_mm);
  const double far_rad = (by_share ? options.distinct_deg : 2.0) * M_PI / 180.0;
  for (std::size_t j = 0; j < result.starts.size(); ++j) {
    StartReport& other = result.starts[j];
    if (static_cast<int>(j) == result.best) continue;
    const bool close = by_share ? other.inlier_share >= (1.0 - options.share_margin) * best.inlier_share
                                : other.score_mm <= (1.0 + options.ambiguity) * best.score_mm;
    if (!close) continue;
    const Eigen::Isometry3d between = other.T_probe * best.T_probe.inverse();
    const bool elsewhere =
        rotation_angle(between) > far_rad || (other.T_probe * centre - best.T_probe * centre).norm() > far_mm;
    if (!elsewhere) continue;
    if (by_share) {
      const std::vector<char>& b = masks[static_cast<std::size_t>(result.best)];
      std::size_t best_only = 0, other_only = 0;
      for (std::size_t i = 0; i < subset.size(); ++i) {
        best_only += b[i] && !masks[j][i];
        other_only += masks[j][i] && !b[i];
      }
      other.best_only_share = static_cast<double>(best_only) / static_cast<double>(subset.size());
      other.only_share = static_cast<double>(other_only) / static_cast<double>(subset.size());
      other.separated = separated(best_only, other_only, subset.size(), options);
      if (other.separated) continue;
    }
    if (result.runner_up < 0 || better(other, result.starts[static_cast<std::size_t>(result.runner_up)])) {
      result.ambiguous = true;
      result.runner_up = static_cast<int>(j);
    }
  }
  return result;
}

}  // namespace conform
