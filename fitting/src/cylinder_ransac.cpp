#include "cylinder_ransac.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>

#include "conform/core/random.h"

namespace conform::detail {
namespace {

// A hypothesis from two oriented points (the construction of Schnabel, Wahl & Klein 2007, Sec. 4.3): the axis is
// perpendicular to both surface normals, a = n1 x n2; projected along a, the two normal lines meet on the axis.
bool hypothesis(const Eigen::Vector3d& p1, const Eigen::Vector3d& n1, const Eigen::Vector3d& p2,
                const Eigen::Vector3d& n2, const RansacSettings& s, Cylinder* model, bool* parallel) {
  const Eigen::Vector3d cross = n1.cross(n2);
  const double sin_angle = cross.norm();
  *parallel = sin_angle < s.sin_min_normal_angle;
  if (*parallel) return false;
  const Eigen::Vector3d a = cross / sin_angle;
  if (s.cos_prior > 0.0 && std::abs(a.dot(s.axis_prior)) < s.cos_prior) return false;
  // Project onto the plane through the origin across the axis; n1, n2 already lie in it (both are perpendicular to a).
  const Eigen::Vector3d q1 = p1 - p1.dot(a) * a;
  const Eigen::Vector3d q2 = p2 - p2.dot(a) * a;
  // q1 + t n1 = q2 + u n2: crossing with n2 gives t (n1 x n2) = (q2 - q1) x n2.
  const double t = (q2 - q1).cross(n2).dot(cross) / (sin_angle * sin_angle);
  const Eigen::Vector3d c = q1 + t * n1;
  const double radius = 0.5 * ((q1 - c).norm() + (q2 - c).norm());
  if (!std::isfinite(radius) || radius <= 0.0 || radius < s.min_radius_mm || radius > s.max_radius_mm) return false;
  model->axis_point = c;
  model->axis_direction = a;
  model->radius_mm = radius;
  return true;
}

// The seeded subset the hypotheses are drawn from and scored on: a partial Fisher-Yates shuffle of the indices.
std::vector<int> seeded_subset(std::size_t n, int count, Random& random) {
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  const std::size_t m = std::min<std::size_t>(n, static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < m; ++i) {
    const std::size_t j = i + static_cast<std::size_t>(random.below(n - i));
    std::swap(all[i], all[j]);
  }
  all.resize(m);
  return all;
}

// MSAC cost (Torr & Zisserman 2000): sum of min(d^2, threshold^2), a disagreeing normal counting as threshold^2.
// Stops early once it exceeds `bound` (the best so far), since such a hypothesis cannot win.
double msac_cost(const Cylinder& model, const std::vector<Eigen::Vector3d>& points,
                 const std::vector<Eigen::Vector3d>& normals, const std::vector<int>& subset, const RansacSettings& s,
                 double bound, int* inliers) {
  const double t2 = s.threshold_mm * s.threshold_mm;
  double cost = 0.0;
  int count = 0;
  for (int i : subset) {
    double d = 0.0;
    if (agrees(model, points[static_cast<std::size_t>(i)], normals[static_cast<std::size_t>(i)], s.threshold_mm,
               s.cos_normal, &d)) {
      cost += d * d;
      ++count;
    } else {
      cost += t2;
    }
    if (cost >= bound) break;
  }
  *inliers = count;
  return cost;
}

// Samples needed to draw one all-inlier pair with the given confidence (Fischler & Bolles 1981).
int required_iterations(double inlier_ratio, double confidence) {
  const double good_pair = inlier_ratio * inlier_ratio;
  if (good_pair <= 0.0) return std::numeric_limits<int>::max();
  if (good_pair >= 1.0) return 1;
  const double k = std::log(1.0 - confidence) / std::log(1.0 - good_pair);
  return k >= 1e9 ? std::numeric_limits<int>::max() : static_cast<int>(std::ceil(k));
}

}  // namespace

bool agrees(const Cylinder& model, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double threshold_mm,
            double cos_normal, double* distance) {
  const Eigen::Vector3d q = p - model.axis_point;
  const Eigen::Vector3d radial = q - q.dot(model.axis_direction) * model.axis_direction;
  const double rho = radial.norm();
  *distance = rho - model.radius_mm;
  if (std::abs(*distance) > threshold_mm) return false;
  return std::abs(n.dot(radial)) >= cos_normal * rho;
}

RansacOutcome ransac_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                              const RansacSettings& s) {
  Random random(s.seed);
  const std::vector<int> subset = seeded_subset(points.size(), s.sample_points, random);
  RansacOutcome out;
  double best_cost = std::numeric_limits<double>::infinity();
  int needed = s.max_iterations;
  while (out.iterations < std::min(s.max_iterations, std::max(s.min_iterations, needed))) {
    ++out.iterations;
    const auto i = static_cast<std::size_t>(subset[random.below(subset.size())]);
    const auto j = static_cast<std::size_t>(subset[random.below(subset.size())]);
    if (i == j) continue;
    Cylinder model;
    bool parallel = false;
    if (!hypothesis(points[i], normals[i], points[j], normals[j], s, &model, &parallel)) {
      out.parallel_normal_samples += parallel ? 1 : 0;
      continue;
    }
    int count = 0;
    const double cost = msac_cost(model, points, normals, subset, s, best_cost, &count);
    if (cost < best_cost) {
      best_cost = cost;
      out.model = model;
      out.found = true;
      needed = required_iterations(static_cast<double>(count) / static_cast<double>(subset.size()), s.confidence);
    }
  }
  if (!out.found) return out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double d = 0.0;
    if (agrees(out.model, points[i], normals[i], s.threshold_mm, s.cos_normal, &d))
      out.inliers.push_back(static_cast<int>(i));
  }
  return out;
}

}  // namespace conform::detail
