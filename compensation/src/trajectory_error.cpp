#include "conform/compensation/trajectory_error.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

#include "path_closure.h"

namespace conform {
namespace {

// Distance of x to the polyline through `path` near its vertex i (the edges before and after it).
double distance_near(const std::vector<Eigen::Vector3d>& path, bool closed, std::size_t i, const Eigen::Vector3d& x) {
  const std::size_t n = path.size();
  double best = (path[i] - x).norm();
  const auto edge = [&](std::size_t a) {
    const Eigen::Vector3d& p = path[a];
    const Eigen::Vector3d d = path[(a + 1) % n] - p;
    const double l2 = d.squaredNorm();
    const double t = l2 > 0.0 ? std::clamp((x - p).dot(d) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, (p + t * d - x).norm());
  };
  if (closed || i + 1 < n) edge(i);
  if (closed || i > 0) edge((i + n - 1) % n);
  return best;
}

}  // namespace

TrajectoryError trajectory_error(const Trajectory& estimate, const Trajectory& truth, const Trajectory& nominal) {
  const std::size_t n = estimate.points.size();
  if (truth.points.size() != n || nominal.points.size() != n || estimate.normals.size() != n ||
      truth.normals.size() != n) {
    throw Error("trajectory error: the trajectories differ in length (" + std::to_string(n) + " rows estimated, " +
                std::to_string(truth.points.size()) + " in the truth, " + std::to_string(nominal.points.size()) +
                " nominal)");
  }
  TrajectoryError e;
  if (n == 0) return e;
  const KdTree tree(truth.points);
  const bool closed = detail::rows_close(truth.points);
  double path_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    // The nearest truth vertex and its two edges: exact while rows are closer together than the path bends.
    const auto near = static_cast<std::size_t>(tree.nearest(estimate.points[i].cast<float>()));
    const double d = distance_near(truth.points, closed, near, estimate.points[i]);
    path_sum += d;
    e.path_max_mm = std::max(e.path_max_mm, d);
  }
  e.path_mean_mm = path_sum / static_cast<double>(n);
  double sum = 0.0, sum_sq = 0.0, angle_sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = (estimate.points[i] - truth.points[i]).norm();
    sum += d;
    sum_sq += d * d;
    if (d > e.max_mm) e.max_mm = d, e.worst_row = i;
    const double angle =
        std::acos(std::clamp(estimate.normals[i].normalized().dot(truth.normals[i].normalized()), -1.0, 1.0)) * 180.0 /
        M_PI;
    angle_sum += angle;
    e.normal_max_deg = std::max(e.normal_max_deg, angle);
    if (i == 0) continue;
    const Eigen::Vector3d step =
        (estimate.points[i] - nominal.points[i]) - (estimate.points[i - 1] - nominal.points[i - 1]);
    const Eigen::Vector3d true_step =
        (truth.points[i] - nominal.points[i]) - (truth.points[i - 1] - nominal.points[i - 1]);
    e.max_step_mm = std::max(e.max_step_mm, step.norm());
    const auto turn = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
    };
    e.normal_step_max_deg = std::max(e.normal_step_max_deg, turn(estimate.normals[i], estimate.normals[i - 1]));
    e.truth_normal_step_max_deg = std::max(e.truth_normal_step_max_deg, turn(truth.normals[i], truth.normals[i - 1]));
    e.truth_step_mm = std::max(e.truth_step_mm, true_step.norm());
  }
  const auto count = static_cast<double>(n);
  e.mean_mm = sum / count;
  e.rms_mm = std::sqrt(sum_sq / count);
  e.normal_mean_deg = angle_sum / count;
  return e;
}

}  // namespace conform
