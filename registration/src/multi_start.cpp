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

double size_of(const std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  return box.diagonal().norm();
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
  MultiStartResult result;
  for (const CoarseStart& start : starts) {
    IcpOptions probe = options.probe;
    probe.progress = nullptr;
    const IcpResult r = icp(subset, reference, start.T_ref_scan, probe);
    StartReport report;
    report.label = start.label;
    report.T_start = start.T_ref_scan;
    report.T_probe = r.T_ref_scan;
    report.score_mm = truncated_rms(subset, r.T_ref_scan, reference, cap);
    report.inlier_fraction = r.inlier_fraction;
    result.starts.push_back(report);
    if (result.best < 0 || report.score_mm < result.starts[static_cast<std::size_t>(result.best)].score_mm) {
      result.best = static_cast<int>(result.starts.size()) - 1;
    }
  }
  const StartReport& best = result.starts[static_cast<std::size_t>(result.best)];
  const Eigen::Vector3d centre =
      std::accumulate(subset.begin(), subset.end(), Eigen::Vector3d(Eigen::Vector3d::Zero())) /
      static_cast<double>(subset.size());
  const double far_mm = 0.01 * size_of(subset);
  for (std::size_t j = 0; j < result.starts.size(); ++j) {
    const StartReport& other = result.starts[j];
    if (static_cast<int>(j) == result.best || other.score_mm > (1.0 + options.ambiguity) * best.score_mm) continue;
    const Eigen::Isometry3d between = other.T_probe * best.T_probe.inverse();
    const bool elsewhere = rotation_angle(between) > 2.0 * M_PI / 180.0 ||
                           (other.T_probe * centre - best.T_probe * centre).norm() > far_mm;
    if (elsewhere &&
        (result.runner_up < 0 || other.score_mm < result.starts[static_cast<std::size_t>(result.runner_up)].score_mm)) {
      result.ambiguous = true;
      result.runner_up = static_cast<int>(j);
    }
  }
  return result;
}

}  // namespace conform
