#include "symmetry_starts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

#include <Eigen/Geometry>

namespace conform::detail {

namespace {

// The step of the turns probed about a near-axisymmetric reference's axis (symmetry_starts): 15 deg reaches every
// index of a part with up to 12 equal features round its axis within half their spacing.
constexpr double kAxialTurnDeg = 15.0;
// slide_starts: the reference along its longest axis at least this many times as long as the scan,
constexpr double kSlideLength = 1.5;
// and this many times as long as it is wide (a profile, a tube, a bar; not a plate, where a stretch would need a
// search in two directions).
constexpr double kLongPart = 3.0;

}  // namespace

std::vector<CoarseStart> symmetry_starts(const StartReport& best, const std::vector<Eigen::Vector3d>& reference,
                                         double similarity) {
  std::vector<CoarseStart> out;
  if (reference.size() < 3) return out;
  const PrincipalAxes axes = principal_axes(reference);
  const auto add = [&](const Eigen::Vector3d& axis, double degrees, const std::string& about) {
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() = Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()).toRotationMatrix();
    turn.translation() = axes.centroid - turn.linear() * axes.centroid;
    out.push_back({best.label + " turned " + std::to_string(static_cast<int>(degrees)) + " deg about " + about,
                   turn * best.T_probe});
  };
  const auto name = [](int k) { return std::to_string(k + 1); };
  for (int k = 0; k < 3; ++k) {
    add(axes.axes.col(k), 180.0, "reference axis " + name(k));
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double u = axes.variances(i), v = axes.variances(j);
    if (std::abs(u - v) > similarity * std::max(u, v)) continue;
    for (double degrees = kAxialTurnDeg; degrees < 359.0; degrees += kAxialTurnDeg) {
      if (std::abs(degrees - 180.0) > 1.0) {
        add(axes.axes.col(k), degrees > 180.0 ? degrees - 360.0 : degrees, "reference axis " + name(k));
      }
    }
    for (double degrees = kAxialTurnDeg; degrees < 179.0; degrees += kAxialTurnDeg) {
      if (std::abs(degrees - 90.0) <= 1.0) continue;  // reference axis j: its half turn is one of the principal ones
      const double a = degrees * M_PI / 180.0;
      add(std::cos(a) * axes.axes.col(i) + std::sin(a) * axes.axes.col(j), 180.0,
          "the axis " + std::to_string(static_cast<int>(degrees)) + " deg from reference axis " + name(i) +
              " towards " + name(j));
    }
  }
  return out;
}

std::vector<CoarseStart> slide_starts(const std::vector<StartReport>& bases,
                                      const std::vector<Eigen::Vector3d>& reference,
                                      const std::vector<Eigen::Vector3d>& scan, double step_mm,
                                      std::size_t max_shifts) {
  std::vector<CoarseStart> out;
  if (reference.size() < 3 || scan.empty() || !(step_mm > 0.0) || max_shifts == 0) return out;
  const PrincipalAxes axes = principal_axes(reference);
  // The extent of `points` moved by T along axis k of the reference.
  const auto extent = [&](const std::vector<Eigen::Vector3d>& points, const Eigen::Isometry3d& T, int k) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Eigen::Vector3d& p : points) {
      const double t = axes.axes.col(k).dot(T * p);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    return std::pair<double, double>(lo, hi);
  };
  const Eigen::Isometry3d identity = Eigen::Isometry3d::Identity();
  const auto [ref_lo, ref_hi] = extent(reference, identity, 0);
  const auto [across_lo, across_hi] = extent(reference, identity, 1);
  if (ref_hi - ref_lo < kLongPart * (across_hi - across_lo)) return out;
  for (const StartReport& base : bases) {
    const auto [scan_lo, scan_hi] = extent(scan, base.T_probe, 0);
    if (ref_hi - ref_lo < kSlideLength * (scan_hi - scan_lo)) continue;
    // Shifts s with the scan's extent within the reference's: ref_lo - scan_lo <= s <= ref_hi - scan_hi.
    const double from = ref_lo - scan_lo, to = ref_hi - scan_hi;
    const double step = std::max(step_mm, (to - from) / static_cast<double>(max_shifts));
    for (double s = std::ceil(from / step) * step; s <= to; s += step) {
      if (std::abs(s) < 0.5 * step) continue;
      out.push_back({base.label + " slid " + std::to_string(static_cast<long>(std::lround(s))) +
                         " mm along reference axis 1",
                     Eigen::Translation3d(s * axes.axes.col(0)) * base.T_probe});
    }
  }
  return out;
}

// Each base pose shifted through each thin wall: by -t, 0 or +t along each of the wall's normal directions (reference
// frame), every combination but no shift, labelled "... shifted through a 5.0 mm wall (+1, 0, -1)".
std::vector<CoarseStart> wall_starts(const std::vector<StartReport>& bases, const std::vector<ThinWall>& walls) {
  std::vector<CoarseStart> out;
  for (const StartReport& base : bases) {
    for (const ThinWall& wall : walls) {
      const auto m = static_cast<int>(wall.directions.size());
      int combinations = 1;
      for (int k = 0; k < m; ++k) combinations *= 3;
      for (int c = 1; c < combinations; ++c) {  // c in base 3, digit k the step along direction k: 0, +1, -1
        Eigen::Vector3d shift = Eigen::Vector3d::Zero();
        std::string steps;
        for (int k = 0, rest = c; k < m; ++k, rest /= 3) {
          const int step = rest % 3 == 2 ? -1 : rest % 3;
          shift += step * wall.thickness_mm * wall.directions[static_cast<std::size_t>(k)];
          steps += (k > 0 ? ", " : "") + std::string(step > 0 ? "+1" : step < 0 ? "-1" : "0");
        }
        char thickness[32];
        std::snprintf(thickness, sizeof thickness, "%.1f", wall.thickness_mm);
        out.push_back({base.label + " shifted through a " + thickness + " mm wall (" + steps + ")",
                       Eigen::Translation3d(shift) * base.T_probe});
      }
    }
  }
  return out;
}

}  // namespace conform::detail
