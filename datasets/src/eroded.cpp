#include "conform/datasets/eroded.h"

#include <algorithm>
#include <cmath>

#include "conform/core/error.h"
#include "conform/core/random.h"

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
    const double half_width = c.inner_radius_mm > 0.0 ? 0.5 * (c.radius_mm - c.inner_radius_mm) : c.radius_mm;
    if (!(c.inner_radius_mm >= 0.0) || !(c.inner_radius_mm < c.radius_mm)) {
      return fail("crater inner radius must be in [0, radius)");
    }
    if (!(c.radius_y_mm >= 0.0) || !std::isfinite(c.radius_y_mm) ||
        (c.radius_y_mm > 0.0 && (c.inner_radius_mm > 0.0 || c.lip_mm > 0.0))) {
      return fail("crater y radius must be >= 0 mm (an elongated crater has no inner radius and no lip)");
    }
    const double narrowest = c.radius_y_mm > 0.0 ? std::min(half_width, c.radius_y_mm) : half_width;
    if (c.depth_mm > 0.5 * narrowest) return fail("crater depth must be at most half its (half-)width (a smooth pit)");
    if (!(c.lip_mm >= 0.0) || !(c.lip_width_mm >= 0.0) || !std::isfinite(c.lip_mm + c.lip_width_mm) ||
        (c.lip_mm > 0.0 && !(c.lip_width_mm > 0.0))) {
      return fail("crater lip height and width must be >= 0 mm (a width when there is a lip)");
    }
  }
  for (const Bump& b : bumps) {
    if (!positive(b.radius_mm) || !positive(b.height_mm) || !std::isfinite(b.x_mm + b.y_mm)) {
      return fail("bump radius and height must be > 0 mm, its centre finite");
    }
  }
  if (!std::isfinite(reference_offset_mm) || !std::isfinite(reference_tilt_deg) || std::abs(reference_tilt_deg) > 10.0) {
    return fail("reference offset must be finite and its tilt within +-10 deg");
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

namespace {

// D (1 - q)^3 for q = (s / h)^2 < 1: C2 at s = h.
double pit(double depth, double s, double h) {
  const double q = s * s / (h * h);
  return q < 1.0 ? depth * (1.0 - q) * (1.0 - q) * (1.0 - q) : 0.0;
}

}  // namespace

double crater_depth(const ErodedOptions& o, double x, double y) {
  double depth = 0.0;
  for (const Crater& c : o.craters) {
    const double rho = std::hypot(x - c.x_mm, y - c.y_mm);
    if (c.radius_y_mm > 0.0) {
      const double qx = (x - c.x_mm) / c.radius_mm, qy = (y - c.y_mm) / c.radius_y_mm;
      depth = std::max(depth, pit(c.depth_mm, std::sqrt(qx * qx + qy * qy), 1.0));
    } else if (c.inner_radius_mm > 0.0) {
      const double h = 0.5 * (c.radius_mm - c.inner_radius_mm);
      depth = std::max(depth, pit(c.depth_mm, rho - (c.inner_radius_mm + h), h));
    } else {
      depth = std::max(depth, pit(c.depth_mm, rho, c.radius_mm));
    }
  }
  return depth;
}

double raised_height(const ErodedOptions& o, double x, double y) {
  double height = 0.0;
  for (const Crater& c : o.craters) {
    const double t = (std::hypot(x - c.x_mm, y - c.y_mm) - c.radius_mm) / std::max(c.lip_width_mm, 1e-300);
    if (c.lip_mm > 0.0 && t > 0.0 && t < 1.0) height = std::max(height, c.lip_mm * std::pow(std::sin(M_PI * t), 2));
  }
  for (const Bump& b : o.bumps) height = std::max(height, pit(b.height_mm, std::hypot(x - b.x_mm, y - b.y_mm), b.radius_mm));
  return height;
}

ErodedScan generate_eroded(const ErodedOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw Error("generate eroded: " + error);
  ErodedScan scan;
  scan.rows = o.rows;
  scan.cols = o.cols;
  Random noise(o.seed, 0);
  const double tilt = std::tan(o.reference_tilt_deg * M_PI / 180.0);
  for (int r = 0; r < o.rows; ++r) {
    for (int c = 0; c < o.cols; ++c) {
      const double x = -0.5 * o.length_mm + o.length_mm * c / (o.cols - 1);
      const double y = -0.5 * o.width_mm + o.width_mm * r / (o.rows - 1);
      const Eigen::Vector3d p = blade_point(o, x, y);
      scan.reference.push_back(p + Eigen::Vector3d(0.0, 0.0, o.reference_offset_mm + tilt * x));
      Eigen::Vector3d e = p - (crater_depth(o, x, y) - raised_height(o, x, y)) * blade_normal(o, x, y);
      e.z() += o.noise_mm * noise.normal();
      scan.eroded.push_back(e);
    }
  }
  for (const Crater& c : o.craters) {
    std::vector<Eigen::Vector3d> rim;
    for (int i = 0; i < o.rim_points; ++i) {
      const double t = 2.0 * M_PI * i / o.rim_points;
      const double ry = c.radius_y_mm > 0.0 ? c.radius_y_mm : c.radius_mm;
      rim.push_back(blade_point(o, c.x_mm + c.radius_mm * std::cos(t), c.y_mm + ry * std::sin(t)));
    }
    scan.rims.push_back(std::move(rim));
    scan.max_depth_mm = std::max(scan.max_depth_mm, c.depth_mm);
  }
  return scan;
}

}  // namespace conform
