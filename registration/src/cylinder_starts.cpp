#include "cylinder_starts.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include "conform/core/error.h"
#include "conform/fitting/cylinder.h"
#include "conform/registration/downsample.h"

namespace conform::detail {

namespace {

// The points each fit sees at most (evenly strided).
constexpr std::size_t kCylinderFitPoints = 20000;
// The radii of the scan's and the reference's cylinders agree within this share of the reference's.
constexpr double kCylinderRadiusShare = 0.1;
// The finest turn about the axis tried.
constexpr double kMinTurnDeg = 0.5;

CylinderFitResult fit(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals) {
  CylinderFitOptions options;
  if (normals.size() == points.size()) return fit_cylinder(points, normals, options);
  Cloud cloud;
  cloud.points.reserve(points.size());
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3f q = p.cast<float>();
    cloud.points.push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
  }
  return fit_cylinder(cloud, options);
}

}  // namespace

std::vector<CoarseStart> cylinder_starts(const std::vector<Eigen::Vector3d>& scan,
                                         const std::vector<Eigen::Vector3d>& reference,
                                         const std::vector<Eigen::Vector3d>& reference_normals, double turn_step_mm) {
  std::vector<CoarseStart> out;
  if (scan.size() < 6 || reference.size() < 6) return out;
  const std::vector<Eigen::Vector3d> scan_points = stride_downsample(scan, kCylinderFitPoints);
  std::vector<Eigen::Vector3d> reference_points, normals;
  const std::size_t stride = (reference.size() + kCylinderFitPoints - 1) / kCylinderFitPoints;
  for (std::size_t i = 0; i < reference.size(); i += stride) {
    reference_points.push_back(reference[i]);
    if (reference_normals.size() == reference.size()) normals.push_back(reference_normals[i]);
  }
  CylinderFitResult s, r;
  try {
    s = fit(scan_points, {});
    if (!s.ok) return out;
    r = fit(reference_points, normals);
    if (!r.ok) return out;
  } catch (const Error&) {  // points on a line, or all in one place: no cylinder, no start
    return out;
  }
  if (std::abs(s.cylinder.radius_mm - r.cylinder.radius_mm) > kCylinderRadiusShare * r.cylinder.radius_mm) return out;
  // The scan's farthest point from its axis sets the step; its extent along the axis is placed at either end of the
  // reference's (a scan of a tube's whole length lies between its ends; a centroid's place along the axis moves
  // with the cut of an end over the arc scanned).
  const Eigen::Vector3d& scan_axis = s.cylinder.axis_direction;
  double farthest = 0.0;
  double scan_low = std::numeric_limits<double>::infinity(), scan_high = -scan_low;
  for (const Eigen::Vector3d& p : scan_points) {
    const Eigen::Vector3d d = p - s.cylinder.axis_point;
    const double t = d.dot(scan_axis);
    farthest = std::max(farthest, (d - t * scan_axis).norm());
    scan_low = std::min(scan_low, t);
    scan_high = std::max(scan_high, t);
  }
  const Eigen::Vector3d& axis = r.cylinder.axis_direction;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const Eigen::Vector3d& p : reference_points) {
    low = std::min(low, (p - r.cylinder.axis_point).dot(axis));
    high = std::max(high, (p - r.cylinder.axis_point).dot(axis));
  }
  const double step_deg = std::max(kMinTurnDeg, turn_step_mm / std::max(farthest, 1e-9) * 180.0 / M_PI);
  const int turns = std::max(1, static_cast<int>(std::ceil(360.0 / step_deg - 1e-9)));
  for (const int sign : {1, -1}) {
    const Eigen::Quaterniond onto =
        Eigen::Quaterniond::FromTwoVectors(scan_axis, static_cast<double>(sign) * axis);
    // The scan's axis point goes to the reference's moved by `along`: its low end at the reference's end it maps to,
    // or its high end.
    std::vector<double> places = {sign > 0 ? low - scan_low : high + scan_low,
                                  sign > 0 ? high - scan_high : low + scan_high};
    if (std::abs(places[1] - places[0]) <= turn_step_mm) places.pop_back();
    for (std::size_t e = 0; e < places.size(); ++e) {
      for (int k = 0; k < turns; ++k) {
        const double degrees = 360.0 * k / turns;
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.linear() = (Eigen::AngleAxisd(degrees * M_PI / 180.0, axis) * onto).toRotationMatrix();
        T.translation() = r.cylinder.axis_point + places[e] * axis - T.linear() * s.cylinder.axis_point;
        char label[64];
        std::snprintf(label, sizeof label, "cylinder axis %c end %zu turn %.1f", sign > 0 ? '+' : '-', e + 1, degrees);
        out.push_back({label, T, true});
      }
    }
  }
  return out;
}

}  // namespace conform::detail
