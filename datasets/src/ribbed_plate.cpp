#include "conform/datasets/ribbed_plate.h"

#include <algorithm>
#include <cmath>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {

namespace {

// smoothstep((h + ramp - |u|) / ramp) and its derivative with respect to u.
void step(double u, double half, double ramp, double* value, double* slope) {
  const double t = (half + ramp - std::abs(u)) / ramp;
  if (t >= 1.0) {
    *value = 1.0;
    *slope = 0.0;
  } else if (t <= 0.0) {
    *value = 0.0;
    *slope = 0.0;
  } else {
    *value = t * t * (3.0 - 2.0 * t);
    *slope = 6.0 * t * (1.0 - t) * (u > 0.0 ? -1.0 : 1.0) / ramp;
  }
}

// z and its gradient (dz/dx, dz/dy).
double height_and_gradient(const RibbedPlateOptions& o, double x, double y, Eigen::Vector2d* gradient) {
  double sy = 0.0, dsy = 0.0;
  step(y, 0.5 * o.rib_length_mm, o.ramp_mm, &sy, &dsy);
  double z = 0.0;
  Eigen::Vector2d g = Eigen::Vector2d::Zero();
  for (int k = 0; k < o.ribs; ++k) {
    const double xk = (k - 0.5 * (o.ribs - 1)) * o.rib_pitch_mm;
    double sx = 0.0, dsx = 0.0;
    step(x - xk, 0.5 * o.rib_width_mm, o.ramp_mm, &sx, &dsx);
    z += o.rib_height_mm * sx * sy;
    g += o.rib_height_mm * Eigen::Vector2d(dsx * sy, sx * dsy);
  }
  if (gradient != nullptr) *gradient = g;
  return z;
}

}  // namespace

bool RibbedPlateOptions::IsValid(std::string* error) const {
  std::string why;
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(length_mm) || !positive(width_mm) || !positive(rib_pitch_mm) || !positive(rib_width_mm) ||
      !positive(rib_height_mm) || !positive(rib_length_mm) || !positive(ramp_mm)) {
    why = "every size must be finite and > 0 mm";
  } else if (ribs < 0 || ribs > 1000) {
    why = "ribs must be in [0, 1000]";
  } else if ((ribs - 1) * rib_pitch_mm + rib_width_mm + 2.0 * ramp_mm > length_mm ||
             rib_length_mm + 2.0 * ramp_mm > width_mm) {
    why = "the ribs do not fit on the plate";
  } else if (points == 0 || points > 100000000) {
    why = "points must be in [1, 1e8]";
  } else if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) {
    why = "noise must be finite and >= 0 mm";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

double ribbed_plate_height(const RibbedPlateOptions& options, double x_mm, double y_mm) {
  return height_and_gradient(options, x_mm, y_mm, nullptr);
}

Eigen::Vector3d ribbed_plate_normal(const RibbedPlateOptions& options, double x_mm, double y_mm) {
  Eigen::Vector2d g;
  height_and_gradient(options, x_mm, y_mm, &g);
  return Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
}

std::vector<Eigen::Vector3d> ribbed_plate_samples(const RibbedPlateOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("ribbed plate: " + why);
  Random position(options.seed, 0), noise(options.seed, 1);
  std::vector<Eigen::Vector3d> points(options.points);
  for (Eigen::Vector3d& p : points) {
    const double x = position.uniform(-0.5 * options.length_mm, 0.5 * options.length_mm);
    const double y = position.uniform(-0.5 * options.width_mm, 0.5 * options.width_mm);
    p = Eigen::Vector3d(x, y, ribbed_plate_height(options, x, y) + options.noise_mm * noise.normal());
  }
  return points;
}

}  // namespace conform
