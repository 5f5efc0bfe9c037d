#include "conform/datasets/eroded.h"

#include <algorithm>
#include <cmath>

#include "conform/core/error.h"
#include "conform/datasets/random.h"

namespace conform {

bool ErodedOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& m) {
    if (error) *error = m;
    return false;
  };
  auto positive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (rows < 4 || cols < 4 || rows > 2000 || cols > 2000) return fail("grid rows and cols must be in [4, 2000]");
  if (!positive(length_mm) || !positive(width_mm)) return fail("length and width must be > 0 mm");
  if (!positive(chord_radius_mm) || !positive(span_radius_mm)) return fail("curvature radii must be > 0 mm");
  if (chord_radius_mm < length_mm || span_radius_mm < width_mm) {
    return fail("curvature radii must be at least the length (chord) and width (span)");
  }
  if (!std::isfinite(twist_per_mm) || std::abs(twist_per_mm) > 0.05) return fail("twist must be within +-0.05 /mm");
  if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) return fail("noise must be >= 0 mm");
  if (rim_points < 8) return fail("rim points must be >= 8");
  for (const Crater& c : craters) {
    if (!positive(c.radius_mm) || !positive(c.depth_mm)) return fail("crater radius and depth must be > 0 mm");
    if (!std::isfinite(c.x_mm) || !std::isfinite(c.y_mm)) return fail("crater centre must be finite");
    if (c.depth_mm > 0.5 * c.radius_mm) return fail("crater depth must be at most half its radius (a smooth pit)");
  }
  return true;
}

Eigen::Vector3d blade_point(const ErodedOptions& o, double x, double y) {
  return {x, y, -x * x / (2.0 * o.chord_radius_mm) - y * y / (2.0 * o.span_radius_mm) + o.twist_per_mm * x * y};
}

Eigen::Vector3d blade_normal(const ErodedOptions& o, double x, double y) {
  const double hx = -x / o.chord_radius_mm + o.twist_per_mm * y, hy = -y / o.span_radius_mm + o.twist_per_mm * x;
  return Eigen::Vector3d(-hx, -hy, 1.0).normalized();
}

double crater_depth(const ErodedOptions& o, double x, double y) {
  double depth = 0.0;
  for (const Crater& c : o.craters) {
    const double q = ((x - c.x_mm) * (x - c.x_mm) + (y - c.y_mm) * (y - c.y_mm)) / (c.radius_mm * c.radius_mm);
    if (q < 1.0) depth = std::max(depth, c.depth_mm * (1.0 - q) * (1.0 - q) * (1.0 - q));
  }
  return depth;
}

ErodedScan generate_eroded(const ErodedOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw Error("generate eroded: " + error);
  ErodedScan scan;
  scan.rows = o.rows;
  scan.cols = o.cols;
  Random noise(o.seed, 0);
  for (int r = 0; r < o.rows; ++r) {
    for (int c = 0; c < o.cols; ++c) {
      const double x = -0.5 * o.length_mm + o.length_mm * c / (o.cols - 1);
      const double y = -0.5 * o.width_mm + o.width_mm * r / (o.rows - 1);
      const Eigen::Vector3d p = blade_point(o, x, y);
      scan.reference.push_back(p);
      Eigen::Vector3d e = p - crater_depth(o, x, y) * blade_normal(o, x, y);
      e.z() += o.noise_mm * noise.normal();
      scan.eroded.push_back(e);
    }
  }
  for (const Crater& c : o.craters) {
    std::vector<Eigen::Vector3d> rim;
    for (int i = 0; i < o.rim_points; ++i) {
      const double t = 2.0 * M_PI * i / o.rim_points;
      rim.push_back(blade_point(o, c.x_mm + c.radius_mm * std::cos(t), c.y_mm + c.radius_mm * std::sin(t)));
    }
    scan.rims.push_back(std::move(rim));
    scan.max_depth_mm = std::max(scan.max_depth_mm, c.depth_mm);
  }
  return scan;
}

}  // namespace conform
