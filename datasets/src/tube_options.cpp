#include "conform/datasets/tube_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "conform/core/error.h"
#include "conform/datasets/tube_grid.h"

namespace conform {

namespace {

bool fail(std::string* error, const std::string& message) {
  if (error != nullptr) *error = message;
  return false;
}

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

bool check_geometry(const TubeOptions& o, std::string* error) {
  if (!std::isfinite(o.radius_mm) || o.radius_mm <= 0.0)
    return fail(error, "radius must be > 0 mm, got " + number(o.radius_mm));
  if (!std::isfinite(o.length_mm) || o.length_mm <= 0.0)
    return fail(error, "length must be > 0 mm, got " + number(o.length_mm));
  if (!std::isfinite(o.arc_rad) || o.arc_rad <= 0.0 || o.arc_rad > 2.0 * M_PI + 1e-12) {
    return fail(error, "arc must be in (0, 360] degrees, got " + number(o.arc_rad * 180.0 / M_PI));
  }
  if (!std::isfinite(o.arc_center_rad)) return fail(error, "arc center azimuth must be finite");
  if (!o.T_world_tube.matrix().allFinite()) return fail(error, "T_world_tube must be finite");
  const Eigen::Matrix3d rotation = o.T_world_tube.linear();
  if (!(rotation.transpose() * rotation).isIdentity(1e-9) || rotation.determinant() < 0.0) {
    return fail(error, "T_world_tube must be a rigid transform (orthonormal rotation, determinant +1)");
  }
  if (o.vertex_count < 0) return fail(error, "vertex count must be >= 0 (0: use the edge length)");
  if (o.vertex_count == 0 && (!std::isfinite(o.edge_mm) || o.edge_mm <= 0.0)) {
    return fail(error, "edge length must be > 0 mm, got " + number(o.edge_mm));
  }
  // Estimated before the integer layout is computed, so that absurd values cannot overflow it.
  const double area = o.radius_mm * std::min(o.arc_rad, 2.0 * M_PI) * o.length_mm;
  const double edge = o.vertex_count > 0 ? std::sqrt(area / (0.866 * static_cast<double>(o.vertex_count))) : o.edge_mm;
  const double estimated = area / (0.433 * edge * edge);
  if (estimated > kMaxTubeTriangles || tube_grid(o).face_count() > static_cast<std::int64_t>(kMaxTubeTriangles)) {
    return fail(error, "edge length " + number(edge) + " mm would make about " + number(estimated) +
                           " triangles (limit " + number(kMaxTubeTriangles) + ")");
  }
  return true;
}

bool check_deformations(const TubeOptions& o, std::string* error) {
  const double angles[] = {o.ovality_azimuth_rad, o.seam_azimuth_rad, o.bow_azimuth_rad};
  for (double a : angles) {
    if (!std::isfinite(a)) return fail(error, "azimuths must be finite");
  }
  if (!std::isfinite(o.ovality_mm) || !std::isfinite(o.seam_height_mm) || !std::isfinite(o.bow_mm)) {
    return fail(error, "ovality, seam height and bow must be finite");
  }
  if (o.seam_height_mm != 0.0 &&
      (!std::isfinite(o.seam_width_mm) || o.seam_width_mm <= 0.0 || o.seam_width_mm > 2.0 * M_PI * o.radius_mm)) {
    return fail(error, "seam width must be in (0, circumference] mm, got " + number(o.seam_width_mm));
  }
  // The radius must stay positive however the deformations add up.
  double worst = std::abs(o.ovality_mm) + std::abs(o.seam_height_mm);
  for (std::size_t i = 0; i < o.bumps.size(); ++i) {
    const TubeBump& b = o.bumps[i];
    const std::string name = "bump " + std::to_string(i + 1);
    if (!std::isfinite(b.azimuth_rad) || !std::isfinite(b.z_mm) || !std::isfinite(b.height_mm)) {
      return fail(error, name + ": azimuth, z and height must be finite");
    }
    if (!std::isfinite(b.radius_mm) || b.radius_mm <= 0.0) {
      return fail(error, name + ": radius must be > 0 mm, got " + number(b.radius_mm));
    }
    worst += std::abs(b.height_mm);
  }
  if (worst >= o.radius_mm) {
    return fail(error, "ovality, seam and bumps add up to " + number(worst) + " mm, not less than the radius " +
                           number(o.radius_mm) + " mm");
  }
  return true;
}

bool check_effects(const TubeOptions& o, std::string* error) {
  if (!std::isfinite(o.noise_mm) || o.noise_mm < 0.0)
    return fail(error, "noise must be >= 0 mm, got " + number(o.noise_mm));
  for (std::size_t i = 0; i < o.holes.size(); ++i) {
    const TubeHole& h = o.holes[i];
    if (!std::isfinite(h.azimuth_rad) || !std::isfinite(h.z_mm) || !std::isfinite(h.radius_mm) || h.radius_mm <= 0.0) {
      return fail(error, "hole " + std::to_string(i + 1) + ": azimuth and z must be finite, radius > 0 mm");
    }
  }
  if (o.random_holes < 0) return fail(error, "random hole count must be >= 0");
  if (o.random_holes > 0 && (!std::isfinite(o.random_hole_radius_mm) || o.random_hole_radius_mm <= 0.0)) {
    return fail(error, "random hole radius must be > 0 mm, got " + number(o.random_hole_radius_mm));
  }
  if (!std::isfinite(o.outlier_fraction) || o.outlier_fraction < 0.0 || o.outlier_fraction >= 1.0) {
    return fail(error, "outlier fraction must be in [0, 1), got " + number(o.outlier_fraction));
  }
  if (o.outlier_fraction > 0.0 && (!std::isfinite(o.outlier_distance_mm) || o.outlier_distance_mm <= 0.0)) {
    return fail(error, "outlier distance must be > 0 mm, got " + number(o.outlier_distance_mm));
  }
  return true;
}

}  // namespace

bool TubeOptions::IsValid(std::string* error) const {
  return check_geometry(*this, error) && check_deformations(*this, error) && check_effects(*this, error);
}

Eigen::Vector3d default_azimuth_reference(const Eigen::Vector3d& axis_direction) {
  int least = 0;
  for (int i = 1; i < 3; ++i) {
    if (std::abs(axis_direction[i]) < std::abs(axis_direction[least])) least = i;
  }
  return Eigen::Vector3d::Unit(least);
}

Eigen::Isometry3d tube_frame(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                             const Eigen::Vector3d& azimuth_reference) {
  if (!axis_point.allFinite() || !axis_direction.allFinite() || !azimuth_reference.allFinite()) {
    throw Error("tube axis: point, direction and azimuth reference must be finite");
  }
  const double length = axis_direction.norm();
  if (length == 0.0) throw Error("tube axis: the direction is the zero vector");
  const Eigen::Vector3d z = axis_direction / length;
  // Gram-Schmidt: the reference's part perpendicular to the axis is the tube's x.
  const Eigen::Vector3d x_raw = azimuth_reference - azimuth_reference.dot(z) * z;
  if (x_raw.norm() < 1e-6 * azimuth_reference.norm() || azimuth_reference.norm() == 0.0) {
    throw Error("tube axis: the azimuth reference is parallel to the axis direction; give another one");
  }
  const Eigen::Vector3d x = x_raw.normalized();
  Eigen::Isometry3d T_world_tube = Eigen::Isometry3d::Identity();
  T_world_tube.linear().col(0) = x;
  T_world_tube.linear().col(1) = z.cross(x);
  T_world_tube.linear().col(2) = z;
  T_world_tube.translation() = axis_point;
  return T_world_tube;
}

}  // namespace conform
