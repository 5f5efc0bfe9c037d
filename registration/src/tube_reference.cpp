#include "conform/registration/tube_reference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"
#include "conform/registration/horn.h"

namespace conform {
namespace {

// A rotation taking the unit axis to +z (any one; the markers fix the rest).
Eigen::Matrix3d axis_to_z(const Eigen::Vector3d& axis) {
  return Eigen::Quaterniond::FromTwoVectors(axis, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

double rms(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v * v;
  return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}

}  // namespace

bool TubeReferenceOptions::IsValid(std::string* error) const {
  std::string why;
  if (!fit.IsValid(&why)) {
    why = "cylinder fit: " + why;
  } else if (!(max_marker_residual_mm > 0.0)) {
    why = "the largest marker residual must be > 0 mm";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

Eigen::Isometry3d tube_frame_from_markers(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                                          const std::vector<Eigen::Vector3d>& markers_scan,
                                          const std::vector<Eigen::Vector3d>& markers_tube,
                                          std::vector<double>* residuals_mm) {
  if (markers_scan.size() != markers_tube.size()) {
    throw Error("tube reference: " + std::to_string(markers_scan.size()) + " markers in the scan but " +
                std::to_string(markers_tube.size()) + " in the tube frame");
  }
  if (markers_scan.size() < 3) throw Error("tube reference: give at least 3 markers (or none)");
  const Eigen::Matrix3d R0 = axis_to_z(axis_direction.normalized());
  // 2D Procrustes across the axis: psi maximises sum t_xy . Rz(psi) q_xy.
  double s_cos = 0.0;
  double s_sin = 0.0;
  double shift = 0.0;
  std::vector<Eigen::Vector3d> q(markers_scan.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    q[i] = R0 * (markers_scan[i] - axis_point);
    const Eigen::Vector3d& t = markers_tube[i];
    s_cos += q[i].x() * t.x() + q[i].y() * t.y();
    s_sin += q[i].x() * t.y() - q[i].y() * t.x();
    shift += t.z() - q[i].z();
  }
  if (std::hypot(s_cos, s_sin) < 1e-9) {
    throw Error(
        "tube reference: the markers do not fix the rotation about the axis (all on the axis, or placed "
        "symmetrically about it): use a non-symmetric layout off the axis");
  }
  const double psi = std::atan2(s_sin, s_cos);
  shift /= static_cast<double>(q.size());
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R0;
  T.translation() = -T.linear() * axis_point + Eigen::Vector3d(0.0, 0.0, shift);
  if (residuals_mm != nullptr) {
    residuals_mm->clear();
    for (std::size_t i = 0; i < q.size(); ++i) residuals_mm->push_back((T * markers_scan[i] - markers_tube[i]).norm());
  }
  return T;
}

namespace {

// The markers span a plane (not one line): their second principal extent is not negligible.
bool spans_a_plane(const std::vector<Eigen::Vector3d>& markers, double collinear_ratio) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& m : markers) mean += m;
  mean /= static_cast<double>(markers.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& m : markers) scatter += (m - mean) * (m - mean).transpose();
  const Eigen::Vector3d eigen = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvalues();  // ascending
  return eigen(2) > 0.0 && std::sqrt(std::max(0.0, eigen(1)) / eigen(2)) >= collinear_ratio;
}

void set_residuals(const Eigen::Isometry3d& T, const std::vector<Eigen::Vector3d>& scan,
                   const std::vector<Eigen::Vector3d>& tube, TubeReferenceResult* result) {
  result->marker_residuals_mm.clear();
  for (std::size_t i = 0; i < scan.size(); ++i) result->marker_residuals_mm.push_back((T * scan[i] - tube[i]).norm());
  result->marker_rms_mm = rms(result->marker_residuals_mm);
  result->marker_max_mm = *std::max_element(result->marker_residuals_mm.begin(), result->marker_residuals_mm.end());
}

// The fitted axis seen in the markers' frame: its angle to z and its distance from z at height z_mean.
void cross_check(const Cylinder& c, const Eigen::Isometry3d& T, double z_mean, TubeReferenceResult* result) {
  const Eigen::Vector3d direction = T.linear() * c.axis_direction;
  const Eigen::Vector3d point = T * c.axis_point;
  result->axis_disagreement_deg = std::acos(std::min(1.0, std::abs(direction.z()))) * 180.0 / 3.141592653589793;
  if (std::abs(direction.z()) < 1e-9) return;
  const Eigen::Vector3d at = point + (z_mean - point.z()) / direction.z() * direction;
  result->axis_offset_mm = at.head<2>().norm();
}

std::string residual_text(const TubeReferenceResult& r, double tolerance_mm) {
  std::ostringstream text;
  text.precision(3);
  text << "marker residuals";
  for (const double d : r.marker_residuals_mm) text << ' ' << d;
  text << " mm (RMS " << r.marker_rms_mm << ", max " << r.marker_max_mm << ", tolerance " << tolerance_mm << " mm)";
  return text.str();
}

}  // namespace

TubeReferenceResult tube_reference(const std::vector<Eigen::Vector3d>& points,
                                   const std::vector<Eigen::Vector3d>& normals,
                                   const std::vector<Eigen::Vector3d>& markers_scan,
                                   const std::vector<Eigen::Vector3d>& markers_tube,
                                   const TubeReferenceOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("tube reference: " + why);
  if (markers_scan.size() != markers_tube.size() || markers_scan.size() == 1 || markers_scan.size() == 2) {
    throw Error("tube reference: give 0 or >= 3 markers, as many in the scan as in the tube frame (got " +
                std::to_string(markers_scan.size()) + " and " + std::to_string(markers_tube.size()) + ")");
  }
  TubeReferenceResult result;
  const bool six_dof = !markers_scan.empty() && spans_a_plane(markers_scan, options.collinear_ratio) &&
                       spans_a_plane(markers_tube, options.collinear_ratio);
  if (six_dof) {
    const HornResult horn = horn_transform(markers_scan, markers_tube);
    if (horn.well_posed) {
      result.T_tube_scan = horn.T_ref_scan;
      result.method = "markers";
      result.free_about_axis = false;
      set_residuals(result.T_tube_scan, markers_scan, markers_tube, &result);
      result.fit = fit_cylinder(points, normals, options.fit);
      if (result.fit.ok) {
        double z_mean = 0.0;
        for (const Eigen::Vector3d& m : markers_tube) z_mean += m.z();
        cross_check(result.fit.cylinder, result.T_tube_scan, z_mean / static_cast<double>(markers_tube.size()),
                    &result);
      }
      result.ok = result.marker_max_mm <= options.max_marker_residual_mm;
      result.termination = (result.ok ? "ok: " : "a marker is farther than the tolerance from its known position: ") +
                           residual_text(result, options.max_marker_residual_mm);
      return result;
    }
  }
  result.fit = fit_cylinder(points, normals, options.fit);
  if (!result.fit.ok) {
    result.termination = "cylinder fit: " + result.fit.termination;
    return result;
  }
  const Cylinder& c = result.fit.cylinder;
  if (markers_scan.empty()) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& p : points) centroid += p;
    centroid /= static_cast<double>(points.size());
    const Eigen::Vector3d foot = c.axis_point + (centroid - c.axis_point).dot(c.axis_direction) * c.axis_direction;
    result.T_tube_scan.linear() = axis_to_z(c.axis_direction);
    result.T_tube_scan.translation() = -result.T_tube_scan.linear() * foot;
    result.free_about_axis = true;
    result.ok = true;
    result.termination = "ok (no markers: rotation about the axis and shift along it are free)";
    return result;
  }
  // Markers on one line: the axis fixes what they cannot. Both axis signs; keep the one the markers agree with.
  double best = std::numeric_limits<double>::infinity();
  for (const double sign : {1.0, -1.0}) {
    std::vector<double> residuals;
    const Eigen::Isometry3d T =
        tube_frame_from_markers(c.axis_point, sign * c.axis_direction, markers_scan, markers_tube, &residuals);
    if (rms(residuals) < best) {
      best = rms(residuals);
      result.T_tube_scan = T;
    }
  }
  result.method = "axis + markers";
  result.free_about_axis = false;
  set_residuals(result.T_tube_scan, markers_scan, markers_tube, &result);
  result.ok = result.marker_max_mm <= options.max_marker_residual_mm;
  result.termination = (result.ok ? "ok (markers on one line, the axis from the cylinder fit): "
                                  : "a marker is farther than the tolerance from its known position: ") +
                       residual_text(result, options.max_marker_residual_mm);
  return result;
}

}  // namespace conform
