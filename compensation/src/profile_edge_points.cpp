#include "conform/compensation/profile_edge_points.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"

namespace conform {
namespace {

std::string describe(const std::string& source, std::size_t index, const Eigen::Vector3d& p) {
  char text[160];
  std::snprintf(text, sizeof(text), "%s: point %zu (%.3f, %.3f, %.3f)", source.c_str(), index, p.x(), p.y(), p.z());
  return text;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

// The principal direction of the points, oriented from the first point towards the last.
Eigen::Vector3d main_axis(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
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
  if (error != nullptr) *error = problem;
  return problem.empty();
}

double estimate_edge_noise_mm(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 3) return 0.0;
  std::vector<double> squared;
  squared.reserve(points.size() - 2);
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    squared.push_back((points[i - 1] - 2.0 * points[i] + points[i + 1]).squaredNorm());
  }
  constexpr double kChiSquare3Median = 2.365973884;
  return std::sqrt(median(std::move(squared)) / (6.0 * kChiSquare3Median));
}

ProfileEdgePointsCheck check_profile_edge_points(const std::vector<Eigen::Vector3d>& points,
                                                 const ProfileEdgePointsOptions& options, const std::string& source) {
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
  std::vector<double> spacing;
  spacing.reserve(points.size() - 1);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Eigen::Vector3d step = points[i] - points[i - 1];
    const double along = step.dot(check.axis);
    if (!(along > 0.0)) {
      char text[200];
      std::snprintf(text, sizeof(text),
                    " is not in measuring order: it lies %.3f mm back along the edge from point %zu (%.3f, %.3f, "
                    "%.3f); the points must follow the edge from its origin",
                    -along, i - 1, points[i - 1].x(), points[i - 1].y(), points[i - 1].z());
      throw Error(describe(source, i, points[i]) + text);
    }
    const double gap = step.norm();
    if (gap > options.max_gap_mm) {
      char text[200];
      std::snprintf(text, sizeof(text), " is %.3f mm from point %zu (%.3f, %.3f, %.3f): a gap larger than %g mm", gap,
                    i - 1, points[i - 1].x(), points[i - 1].y(), points[i - 1].z(), options.max_gap_mm);
      throw Error(describe(source, i, points[i]) + text);
    }
    if (gap > check.max_gap_mm) {
      check.max_gap_mm = gap;
      check.max_gap_index = static_cast<int>(i);
    }
    check.chord_length_mm += gap;
    spacing.push_back(gap);
  }
  check.median_spacing_mm = median(std::move(spacing));
  check.noise_mm = estimate_edge_noise_mm(points);
  return check;
}

}  // namespace conform
