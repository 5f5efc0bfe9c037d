#include "conform/compensation/profile_edge_points.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/core/median.h"

namespace conform {
namespace {

std::string describe(const std::string& source, std::size_t index, const Eigen::Vector3d& p) {
  char text[160];
  std::snprintf(text, sizeof(text), "%s: point %zu (%.3f, %.3f, %.3f)", source.c_str(), index, p.x(), p.y(), p.z());
  return text;
}

// The principal direction of the points, oriented from the first point towards the last.
Eigen::Vector3d main_axis(const std::vector<Eigen::Vector3d>& points) {
  // Relative to the first point: shop coordinates far from the origin lose no digits in the sums.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p - points.front();
  centroid = points.front() + centroid / static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  Eigen::Vector3d axis = solver.eigenvectors().col(2);
  if (axis.dot(points.back() - points.front()) < 0.0) axis = -axis;
  return axis;
}

}  // namespace

bool ProfileEdgePointsOptions::IsValid(std::string* error) const {
  std::string problem;
  if (!(max_gap_mm > 0.0) || !std::isfinite(max_gap_mm)) problem = "max_gap_mm must be positive and finite";
  if (min_points < 4) problem = "min_points must be at least 4";
  if (!(order_tolerance_sigma >= 0.0) || !std::isfinite(order_tolerance_sigma)) {
    problem = "order_tolerance_sigma must be >= 0";
  }
  if (error != nullptr) *error = problem;
  return problem.empty();
}

double estimate_edge_noise_mm(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 3) return 0.0;
  const Eigen::Vector3d axis = main_axis(points);
  std::vector<double> scaled;
  scaled.reserve(points.size() - 2);
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const double h1 = (points[i] - points[i - 1]).dot(axis), h2 = (points[i + 1] - points[i]).dot(axis);
    if (!(h1 > 0.0 && h2 > 0.0)) continue;  // out of order or repeated: no interpolation between them
    // P_i against the chord of its neighbours at its own place along the axis: uneven steps (dropouts) cancel.
    const double w = h1 / (h1 + h2);
    Eigen::Vector3d d = points[i] - (points[i - 1] + w * (points[i + 1] - points[i - 1]));
    d -= d.dot(axis) * axis;
    scaled.push_back(d.squaredNorm() / (1.0 + w * w + (1.0 - w) * (1.0 - w)));
  }
  constexpr double kChiSquare2Median = 1.386294361;  // 2 ln 2
  return std::sqrt(median(std::move(scaled)) / kChiSquare2Median);
}

namespace {

[[noreturn]] void refuse_order(const std::string& source, const std::vector<Eigen::Vector3d>& points, std::size_t i,
                               std::size_t before, double back_mm, double tolerance_mm) {
  char text[360];
  std::snprintf(text, sizeof(text),
                " is not in measuring order: it lies %.3f mm back along the edge from point %zu (%.3f, %.3f, %.3f), "
                "more than the noise allows (%.3f mm); the points must follow the edge from its origin",
                back_mm, before, points[before].x(), points[before].y(), points[before].z(), tolerance_mm);
  throw Error(describe(source, i, points[i]) + text);
}

}  // namespace

ProfileEdgePointsCheck check_profile_edge_points(const std::vector<Eigen::Vector3d>& points,
                                                 const ProfileEdgePointsOptions& options, const std::string& source,
                                                 double noise_mm) {
  std::string problem;
  if (!options.IsValid(&problem)) throw Error(source + ": invalid edge-point options: " + problem);
  if (points.size() < static_cast<std::size_t>(options.min_points)) {
    throw Error(source + ": " + std::to_string(points.size()) + " edge points; at least " +
                std::to_string(options.min_points) + " are needed to fit the edge curve");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) throw Error(describe(source, i, points[i]) + " is not finite");
  }
  ProfileEdgePointsCheck check;
  check.axis = main_axis(points);
  check.noise_mm = estimate_edge_noise_mm(points);
  const double sigma = noise_mm > 0.0 ? noise_mm : check.noise_mm;
  // Two noisy points differ along the axis by sigma sqrt(2): a step back within the tolerance is noise.
  check.order_tolerance_mm = options.order_tolerance_sigma * std::sqrt(2.0) * sigma;
  std::vector<double> along(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) along[i] = (points[i] - points.front()).dot(check.axis);
  double furthest = along[0];
  std::size_t furthest_index = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    if (along[i] < furthest - check.order_tolerance_mm) {
      refuse_order(source, points, i, furthest_index, furthest - along[i], check.order_tolerance_mm);
    }
    if (along[i] < along[i - 1]) ++check.reordered;
    if (along[i] > furthest) furthest = along[i], furthest_index = i;
  }
  // Sorted along the axis (stable: a scan in order stays as it is), exact repeats dropped: O(n log n).
  std::vector<int> order(points.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&along](int a, int b) {
    return along[static_cast<std::size_t>(a)] < along[static_cast<std::size_t>(b)];
  });
  std::vector<double> spacing;
  spacing.reserve(points.size());
  for (int index : order) {
    const auto i = static_cast<std::size_t>(index);
    if (!check.order.empty()) {
      const auto previous = static_cast<std::size_t>(check.order.back());
      const Eigen::Vector3d step = points[i] - points[previous];
      if (step.squaredNorm() <= 0.0) {
        ++check.duplicates;
        continue;
      }
      const double gap = along[i] - along[previous];
      if (gap > options.max_gap_mm) {
        char text[200];
        std::snprintf(text, sizeof(text), " is %.3f mm from point %zu (%.3f, %.3f, %.3f): a gap larger than %g mm",
                      gap, previous, points[previous].x(), points[previous].y(), points[previous].z(),
                      options.max_gap_mm);
        throw Error(describe(source, i, points[i]) + text);
      }
      if (gap > check.max_gap_mm) {
        check.max_gap_mm = gap;
        check.max_gap_index = index;
      }
      check.chord_length_mm += step.norm();
      spacing.push_back(gap);
    }
    check.order.push_back(index);
  }
  if (check.order.size() < static_cast<std::size_t>(options.min_points)) {
    throw Error(source + ": " + std::to_string(check.order.size()) + " distinct edge points; at least " +
                std::to_string(options.min_points) + " are needed to fit the edge curve");
  }
  check.along_mm.reserve(check.order.size());
  for (int index : check.order) check.along_mm.push_back(along[static_cast<std::size_t>(index)]);
  check.median_spacing_mm = median(std::move(spacing));
  // The noise of the points kept, in their order along the axis (repeats would make it look smaller).
  std::vector<Eigen::Vector3d> kept;
  kept.reserve(check.order.size());
  for (int index : check.order) kept.push_back(points[static_cast<std::size_t>(index)]);
  check.noise_mm = estimate_edge_noise_mm(kept);
  return check;
}

}  // namespace conform
