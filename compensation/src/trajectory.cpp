#include "conform/compensation/trajectory.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "conform/compensation/sicp_blend.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {
namespace {

// Arc length of the projection of x onto edge (i, i+1), and its squared distance.
std::pair<double, double> project_on_edge(const Polyline& c, const std::vector<double>& s, std::size_t i,
                                          const Eigen::Vector3d& x, double length) {
  const std::size_t n = c.points.size();
  const Eigen::Vector3d& a = c.points[i];
  const Eigen::Vector3d& b = c.points[(i + 1) % n];
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0.0 ? std::clamp((x - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  const double end = i + 1 < n ? s[i + 1] : length;
  return {s[i] + t * (end - s[i]), (a + t * ab - x).squaredNorm()};
}

}  // namespace

bool ToolNormalOptions::IsValid(std::string* error) const {
  const char* why = nullptr;
  if (!std::isfinite(radius_mm) || radius_mm <= 0.0)
    why = "tool normal radius must be > 0 mm";
  else if (!std::isfinite(slab_mm) || slab_mm <= 0.0)
    why = "tool normal slab must be > 0 mm";
  else if (min_points < 3)
    why = "tool normal fit needs at least 3 points";
  else if (!std::isfinite(max_tilt_rad) || max_tilt_rad <= 0.0)
    why = "tool normal tilt limit must be > 0";
  else if (!std::isfinite(smooth_mm) || smooth_mm < 0.0 || smooth_mm > 1000.0)
    why = "tool normal smoothing must be in [0, 1000] mm";
  if (why == nullptr) return true;
  if (error != nullptr) *error = why;
  return false;
}

std::vector<double> locate_on_contour(const Polyline& contour, const std::vector<double>& s,
                                      const std::vector<Eigen::Vector3d>& points, std::vector<double>* distances_mm) {
  if (contour.points.size() < 2) throw Error("contour: fewer than 2 points");
  const KdTree tree(contour.points);
  const std::size_t n = contour.points.size();
  const double length = conform::length(contour);
  std::vector<double> result(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto i = static_cast<std::size_t>(tree.nearest(points[k].cast<float>()));
    std::pair<double, double> best{s[i], (contour.points[i] - points[k]).squaredNorm()};
    const bool has_next = contour.closed || i + 1 < n;
    const bool has_previous = contour.closed || i > 0;
    if (has_next)
      best = std::min(best, project_on_edge(contour, s, i, points[k], length),
                      [](const auto& a, const auto& b) { return a.second < b.second; });
    if (has_previous)
      best = std::min(best, project_on_edge(contour, s, (i + n - 1) % n, points[k], length),
                      [](const auto& a, const auto& b) { return a.second < b.second; });
    result[k] = best.first;
    if (distances_mm != nullptr) distances_mm->push_back(std::sqrt(best.second));
  }
  return result;
}

Trajectory map_by_segments(const Trajectory& nominal, const Polyline& contour, const ContourSegmentation& g,
                           const std::vector<Eigen::Isometry3d>& T) {
  if (T.size() != g.segments.size()) throw Error("S-ICP trajectory: one transform per segment needed");
  const std::vector<double> s = locate_on_contour(contour, g.arc_length_mm, nominal.points);
  Trajectory out;
  for (std::size_t i = 0; i < nominal.points.size(); ++i) {
    out.points.push_back(blend_point(g, T, s[i], nominal.points[i]));
    out.normals.push_back(blend_normal(g, T, s[i], nominal.normals[i]));
  }
  return out;
}

Trajectory map_rigidly(const Trajectory& nominal, const Eigen::Isometry3d& T) {
  Trajectory out;
  for (std::size_t i = 0; i < nominal.points.size(); ++i) {
    out.points.push_back(T * nominal.points[i]);
    out.normals.push_back((T.linear() * nominal.normals[i]).normalized());
  }
  return out;
}

namespace {

// Least-squares plane of the selected points: their mean and the unit normal on `side`'s side; false for fewer
// than `min_points`.
bool fit_plane(const std::vector<Eigen::Vector3d>& points, const std::vector<bool>& use, std::size_t min_points,
               const Eigen::Vector3d& side, Eigen::Vector3d& mean, Eigen::Vector3d& normal) {
  std::size_t used = 0;
  mean.setZero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (use[i]) mean += points[i], ++used;
  }
  if (used < min_points) return false;
  mean /= static_cast<double>(used);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (use[i]) covariance += (points[i] - mean) * (points[i] - mean).transpose();
  }
  normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvectors().col(0);
  if (normal.dot(side) < 0.0) normal = -normal;
  return true;
}

}  // namespace

std::size_t reestimate_tool_normals(Trajectory& t, const std::vector<Eigen::Vector3d>& scan, const KdTree& tree,
                                    const ToolNormalOptions& o) {
  std::string why;
  if (!o.IsValid(&why)) throw Error("tool normals: " + why);
  std::size_t from_scan = 0;
  std::vector<int> indices;
  std::vector<float> sq;
  std::vector<Eigen::Vector3d> near;
  std::vector<bool> use;
  for (std::size_t k = 0; k < t.points.size(); ++k) {
    const Eigen::Vector3d& p = t.points[k];
    Eigen::Vector3d& normal = t.normals[k];
    tree.radius(p.cast<float>(), static_cast<float>(o.radius_mm), indices, sq);
    near.clear();
    for (int i : indices) {
      const Eigen::Vector3d& q = scan[static_cast<std::size_t>(i)];
      if (std::abs((q - p).dot(normal)) <= o.slab_mm) near.push_back(q);
    }
    // At an edge the slab also holds the top of the flank, which tilts the plane: fit again on the points within
    // 2.5 times the residual RMS of the last fit (the surface's noise), twice.
    use.assign(near.size(), true);
    Eigen::Vector3d mean, fitted;
    bool ok = fit_plane(near, use, o.min_points, normal, mean, fitted);
    for (int pass = 0; ok && pass < 2; ++pass) {
      double sum_sq = 0.0;
      for (const Eigen::Vector3d& q : near) sum_sq += std::pow((q - mean).dot(fitted), 2);
      const double limit = 2.5 * std::sqrt(sum_sq / static_cast<double>(near.size()));
      for (std::size_t i = 0; i < near.size(); ++i) use[i] = std::abs((near[i] - mean).dot(fitted)) <= limit;
      ok = fit_plane(near, use, o.min_points, normal, mean, fitted);
    }
    if (!ok || std::acos(std::clamp(fitted.dot(normal), -1.0, 1.0)) > o.max_tilt_rad) continue;
    normal = fitted;
    ++from_scan;
  }
  return from_scan;
}

void smooth_tool_normals(Trajectory& t, double window_mm) {
  const std::size_t n = t.points.size();
  if (window_mm <= 0.0 || n < 3) return;
  std::vector<double> spacing(n, 0.0);  // spacing[i]: from row i to row i + 1 (the closing edge last)
  for (std::size_t i = 0; i < n; ++i) spacing[i] = (t.points[(i + 1) % n] - t.points[i]).norm();
  std::vector<double> sorted(spacing.begin(), spacing.end() - 1);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const bool closed = spacing[n - 1] <= 3.0 * sorted[sorted.size() / 2];
  const std::vector<Eigen::Vector3d> normals = t.normals;
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector3d sum = normals[i];
    for (int direction : {-1, 1}) {
      double d = 0.0;
      std::size_t j = i;
      for (std::size_t steps = 1; steps < n; ++steps) {
        if (!closed && ((direction < 0 && j == 0) || (direction > 0 && j + 1 == n))) break;
        const std::size_t next = direction > 0 ? (j + 1) % n : (j + n - 1) % n;
        d += spacing[direction > 0 ? j : next];
        if (d >= window_mm || next == i) break;
        sum += (1.0 - d / window_mm) * normals[next];
        j = next;
      }
    }
    if (sum.norm() > 1e-12) t.normals[i] = sum.normalized();
  }
}

void check_trajectory(const Trajectory& t, const std::string& what) {
  if (t.normals.size() != t.points.size()) {
    throw Error(what + ": " + std::to_string(t.normals.size()) + " normals for " + std::to_string(t.points.size()) +
                " points");
  }
  for (std::size_t i = 0; i < t.points.size(); ++i) {
    if (!t.points[i].allFinite() || !t.normals[i].allFinite())
      throw Error(what + ": row " + std::to_string(i + 1) + " is not finite");
    if (std::abs(t.normals[i].norm() - 1.0) > 1e-3)
      throw Error(what + ": row " + std::to_string(i + 1) + ": the tool normal is not of unit length (" +
                  std::to_string(t.normals[i].norm()) + ")");
  }
}

}  // namespace conform
