#include "conform/robot/tool_frames.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include <Eigen/Geometry>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

// A tangent whose part off z is shorter than this fraction of it is taken as parallel to z: its direction off z is
// rounding noise.
constexpr double kParallel = 1e-9;

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

// The neighbour of i in direction `step` (+1/-1) that is a different point, or nothing.
std::optional<std::size_t> distinct_neighbour(const ToolPathPoints& pts, bool closed, std::size_t i, int step) {
  const std::size_t n = pts.positions.size();
  std::size_t j = i;
  for (std::size_t k = 1; k < n; ++k) {
    if (step > 0) {
      if (j + 1 == n) {
        if (!closed) return std::nullopt;
        j = 0;
      } else {
        ++j;
      }
    } else {
      if (j == 0) {
        if (!closed) return std::nullopt;
        j = n - 1;
      } else {
        --j;
      }
    }
    if (pts.positions[j] != pts.positions[i]) return j;
  }
  return std::nullopt;
}

// Central difference over distinct neighbours, one-sided at the ends of an open segment; zero when there is none.
Eigen::Vector3d tangent_at(const ToolPathPoints& pts, bool closed, std::size_t i) {
  const auto next = distinct_neighbour(pts, closed, i, +1);
  const auto prev = distinct_neighbour(pts, closed, i, -1);
  const Eigen::Vector3d& p = pts.positions[i];
  if (next && prev) {
    // Each side normalised, so that uneven steps do not tilt the tangent towards the longer one.
    return (pts.positions[*next] - p).normalized() + (p - pts.positions[*prev]).normalized();
  }
  if (next) return pts.positions[*next] - p;
  if (prev) return p - pts.positions[*prev];
  return Eigen::Vector3d::Zero();
}

// `v` off the unit axis z, normalised; nothing when v is (nearly) parallel to z or zero.
std::optional<Eigen::Vector3d> off_axis(const Eigen::Vector3d& v, const Eigen::Vector3d& z) {
  const Eigen::Vector3d off = v - v.dot(z) * z;
  const double norm = v.norm();
  if (!(norm > 0.0) || off.norm() <= kParallel * norm) return std::nullopt;
  return off.normalized();
}

Eigen::Vector3d least_aligned_axis(const Eigen::Vector3d& z) {
  Eigen::Index axis = 0;
  z.cwiseAbs().minCoeff(&axis);
  return Eigen::Vector3d::Unit(axis);
}

// Turns x about z, the least, so that it lies within `cone` of `preferred` (both off z).
bool limit_roll(const Eigen::Vector3d& z, const Eigen::Vector3d& preferred, double cone, Eigen::Vector3d* x) {
  const auto pref = off_axis(preferred, z);
  if (!pref) return false;
  const double angle = std::atan2(pref->cross(*x).dot(z), pref->dot(*x));  // signed, about z
  if (std::abs(angle) <= cone) return false;
  const double target = std::copysign(cone, angle);
  *x = std::cos(target) * *pref + std::sin(target) * z.cross(*pref);
  return true;
}

void check_input(const ToolPathPoints& pts) {
  const std::size_t n = pts.positions.size();
  if (pts.tool_axes.size() != n || (!pts.hints.empty() && pts.hints.size() != n)) {
    throw Error("tool frames: " + std::to_string(n) + " points but " + std::to_string(pts.tool_axes.size()) +
                " tool axes and " + std::to_string(pts.hints.size()) + " hints");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite(pts.positions[i]) || !finite(pts.tool_axes[i]) || (!pts.hints.empty() && !finite(pts.hints[i]))) {
      throw Error("tool frames: point " + std::to_string(i) + " has a value that is not finite");
    }
    if (!(pts.tool_axes[i].norm() > 0.0)) {
      throw Error("tool frames: point " + std::to_string(i) + " has a zero tool axis");
    }
  }
}

}  // namespace

std::size_t ToolPath::frames() const {
  std::size_t n = 0;
  for (const ToolSegment& s : segments) n += s.frames.size();
  return n;
}

bool ToolFrameOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(roll_cone_rad >= 0.0 && roll_cone_rad <= kPi)) why << "the roll cone must be in [0, 180] deg";
  if (!finite(preferred_x) || !(preferred_x.norm() > 0.0)) why << "the preferred x direction must be finite, not 0";
  if (!(max_jump_ratio == 0.0 || (max_jump_ratio > 1.0 && std::isfinite(max_jump_ratio)))) {
    why << "the jump ratio must be > 1 (0: no check)";
  }
  if (error != nullptr) *error = why.str();
  return why.str().empty();
}

std::vector<ToolFrame> build_tool_frames(const ToolPathPoints& pts, const ToolFrameOptions& options,
                                         ToolFrameFigures* figures) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tool frames: " + why);
  check_input(pts);
  const std::size_t n = pts.positions.size();
  ToolFrameFigures local;
  ToolFrameFigures& fig = figures != nullptr ? *figures : local;

  // A path whose last point repeats its first (the saddle's theta = 2 pi) is closed too.
  const bool closed = pts.closed || (n > 2 && pts.positions.front() == pts.positions.back());
  std::vector<Eigen::Vector3d> z(n);
  std::vector<std::optional<Eigen::Vector3d>> x(n);
  for (std::size_t i = 0; i < n; ++i) {
    z[i] = pts.tool_axes[i].normalized();
    if (i > 0 && pts.positions[i] == pts.positions[i - 1]) ++fig.repeated_points;
    x[i] = off_axis(tangent_at(pts, closed, i), z[i]);
    if (!x[i]) ++fig.parallel_tangents;
  }
  // Carry x over from the previous usable frame, then (for a leading run) back from the next one.
  for (std::size_t i = 1; i < n; ++i) {
    if (!x[i] && x[i - 1]) x[i] = off_axis(*x[i - 1], z[i]);
  }
  for (std::size_t i = n; i-- > 1;) {
    if (!x[i - 1] && x[i]) x[i - 1] = off_axis(*x[i], z[i - 1]);
  }
  std::vector<ToolFrame> frames(n);
  const bool limit = options.roll_cone_rad > 0.0 && options.roll_cone_rad < kPi;
  for (std::size_t i = 0; i < n; ++i) {
    if (!x[i] && !pts.hints.empty()) x[i] = off_axis(pts.hints[i], z[i]);
    if (!x[i]) x[i] = off_axis(least_aligned_axis(z[i]), z[i]);
    Eigen::Vector3d xi = *x[i];
    if (limit && limit_roll(z[i], options.preferred_x, options.roll_cone_rad, &xi)) ++fig.roll_limited;
    frames[i].position = pts.positions[i];
    frames[i].rotation.col(0) = xi;
    frames[i].rotation.col(1) = z[i].cross(xi).normalized();
    frames[i].rotation.col(2) = z[i];
  }
  return frames;
}

double rotation_angle_between(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d d = a.transpose() * b;
  // atan2 of sin and cos of the angle: accurate near 0 and pi, unlike acos of the trace.
  const Eigen::Vector3d axis(d(2, 1) - d(1, 2), d(0, 2) - d(2, 0), d(1, 0) - d(0, 1));
  return std::atan2(0.5 * axis.norm(), 0.5 * (d.trace() - 1.0));
}

void measure_orientation_steps(const ToolPath& path, ToolFrameFigures* figures) {
  std::size_t index = 0;
  for (const ToolSegment& segment : path.segments) {
    for (std::size_t i = 0; i < segment.frames.size(); ++i, ++index) {
      if (i == 0) continue;
      const double step = rotation_angle_between(segment.frames[i - 1].rotation, segment.frames[i].rotation);
      if (step > figures->max_orientation_step_rad) {
        figures->max_orientation_step_rad = step;
        figures->max_step_index = index;
      }
    }
  }
}

}  // namespace conform
