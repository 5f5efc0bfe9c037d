#include "conform/datasets/workpiece.h"

#include <algorithm>
#include <cmath>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {

namespace {

constexpr double kShoulderDepth = 6.0, kPocketDepth = 8.0, kBoreDepth = 10.0, kSlotDepth = 4.0;

// 1 inside (|u| <= half), 0 beyond half + ramp, a smoothstep between.
double inside(double u, double half, double ramp) {
  const double t = std::clamp((half + ramp - std::abs(u)) / ramp, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// 1 for u >= 0 (past the edge), 0 below -ramp.
double beyond(double u, double ramp) {
  const double t = std::clamp((u + ramp) / ramp, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

bool WorkpieceOptions::IsValid(std::string* error) const {
  std::string why;
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(length_mm) || !positive(width_mm) || !positive(ramp_mm)) {
    why = "length, width and ramp must be finite and > 0 mm";
  } else if (!(x_from >= 0.0 && x_from < x_to && x_to <= 1.0)) {
    why = "the window must satisfy 0 <= x_from < x_to <= 1";
  } else if (points == 0 || points > 100000000) {
    why = "points must be in [1, 1e8]";
  } else if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) {
    why = "noise must be finite and >= 0 mm";
  } else if (!(outlier_share >= 0.0 && outlier_share < 1.0)) {
    why = "outlier_share must be in [0, 1)";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

double workpiece_height(const WorkpieceOptions& o, double x, double y) {
  const double L = o.length_mm, W = o.width_mm, r = o.ramp_mm;
  const double shoulder = beyond(y - (0.5 - 0.25) * W, r);
  const double pocket = inside(x + 0.25 * L, 0.125 * L, r) * inside(y + 0.05 * W, 0.15 * W, r);
  const Eigen::Vector2d bore_centre(0.28 * L, -0.25 * W);
  const double bore = inside((Eigen::Vector2d(x, y) - bore_centre).norm(), 0.1 * W, r);
  const double slot = inside(x - 0.22 * L, 0.16 * L, r) * inside(y - 0.12 * W, 0.04 * W, r);
  return -kShoulderDepth * shoulder - kPocketDepth * pocket - kBoreDepth * bore - kSlotDepth * slot;
}

std::vector<Eigen::Vector3d> workpiece_samples(const WorkpieceOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("workpiece: " + why);
  Random position(options.seed, 0), noise(options.seed, 1), outliers(options.seed, 2);
  const double x0 = (options.x_from - 0.5) * options.length_mm, x1 = (options.x_to - 0.5) * options.length_mm;
  const double half_w = 0.5 * options.width_mm;
  std::vector<Eigen::Vector3d> points(options.points);
  for (Eigen::Vector3d& p : points) {
    const double x = position.uniform(x0, x1), y = position.uniform(-half_w, half_w);
    p = Eigen::Vector3d(x, y, workpiece_height(options, x, y) + options.noise_mm * noise.normal());
    if (outliers.uniform() < options.outlier_share) {
      p = Eigen::Vector3d(outliers.uniform(x0, x1), outliers.uniform(-half_w, half_w), outliers.uniform(-20.0, 10.0));
    }
  }
  return points;
}

}  // namespace conform
