#pragma once
// Shared by the registration tests: pose errors against a ground truth, seeded random perturbations, test parts.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "conform/core/mesh.h"
#include "conform/core/random.h"

namespace conform::test {

constexpr double kDeg = M_PI / 180.0;

// The seed stream of the realistic-variation matrices: CONFORM_MATRIX_STREAM=k (default 0) runs a matrix of `count`
// seeds on seeds k count + 1 .. (k + 1) count instead of 1 .. count, so that a change is judged on several
// streams, not tuned to one (run by hand; CI runs stream 0, whose tallies the tests assert). Each seed's share of
// a stepped parameter comes from matrix_index(), the seed's place in its stream.
inline int matrix_stream() {
  const char* value = std::getenv("CONFORM_MATRIX_STREAM");
  return value == nullptr ? 0 : std::max(0, std::atoi(value));
}
// The i-th seed (i = 1 .. count) of the stream.
inline int matrix_seed(int i, int count) { return i + count * matrix_stream(); }
// Where `seed` stands in its stream: 0 .. count - 1.
inline int matrix_index(int seed, int count) { return (seed - 1) % count; }

// Rotation angle of R_est R_true^T (deg) and |t_est - t_true| (mm) of two T_ref_scan.
inline double rotation_error_deg(const Eigen::Isometry3d& est, const Eigen::Isometry3d& truth) {
  const Eigen::Matrix3d R = est.linear() * truth.linear().transpose();
  const Eigen::Vector3d s(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  return std::atan2(0.5 * s.norm(), 0.5 * (R.trace() - 1.0)) / kDeg;
}
inline double translation_error_mm(const Eigen::Isometry3d& est, const Eigen::Isometry3d& truth) {
  return (est.translation() - truth.translation()).norm();
}

// A unit vector uniform on the sphere.
inline Eigen::Vector3d random_direction(Random& random) {
  const double z = random.uniform(-1.0, 1.0), phi = random.uniform(0.0, 2.0 * M_PI);
  const double r = std::sqrt(1.0 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// A rigid motion about `centre`: rotation by an angle uniform in [0, max_angle] about a uniform axis, then a
// translation of length uniform in [0, max_translation] in a uniform direction.
inline Eigen::Isometry3d random_motion(Random& random, double max_angle_rad, double max_translation_mm,
                                       const Eigen::Vector3d& centre) {
  const Eigen::AngleAxisd rotation(random.uniform(0.0, max_angle_rad), random_direction(random));
  const Eigen::Vector3d translation = random.uniform(0.0, max_translation_mm) * random_direction(random);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = rotation.toRotationMatrix();
  T.translation() = centre + translation - T.linear() * centre;
  return T;
}

inline std::vector<Eigen::Vector3d> transformed_points(const std::vector<Eigen::Vector3d>& points,
                                                       const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = T * points[i];
  return out;
}

inline Eigen::Vector3d mean_point(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

// Median and maximum of a list (0 when empty).
struct Spread {
  double median = 0.0;
  double max = 0.0;
};
inline Spread spread_of(std::vector<double> v) {
  if (v.empty()) return {};
  std::sort(v.begin(), v.end());
  return {v[v.size() / 2], v.back()};
}

}  // namespace conform::test
