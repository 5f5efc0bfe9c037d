#include "inspect/inspect_features.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/fitting/cylinder.h"
#include "conform/fitting/revolved.h"

namespace conform::detail {

namespace {

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // atan2 of the cross and dot products: accurate at small angles, where acos of the dot loses half its digits.
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

// The form zone of the points about the fitted feature, `distance` giving each point's residual from it.
template <typename Distance>
void set_form_about(const std::vector<Eigen::Vector3d>& points, const char* reference, const InspectOptions& options,
                    FaceInspection& face, Distance distance) {
  std::vector<double> residuals;
  residuals.reserve(points.size());
  for (const Eigen::Vector3d& p : points) residuals.push_back(distance(p));
  face.form_measured = true;
  face.form_reference = reference;
  face.form = form_zone(residuals, options.form_trim);
}

void measure_plane(const std::vector<Eigen::Vector3d>& points, const InspectOptions& options, FaceInspection& face) {
  const PlaneFit fit = fit_plane(points);
  if (!fit.ok) {
    face.fit_note = "the points lie on a line: no plane to fit";
    return;
  }
  const Eigen::Vector3d& nominal = face.nominal.axis;  // outward
  face.fitted = true;
  face.normal = fit.normal.dot(nominal) >= 0.0 ? fit.normal : Eigen::Vector3d(-fit.normal);
  face.angle_to_nominal_deg = angle_deg(face.normal, nominal);
  // Where the fitted plane crosses the nominal normal line through the face's centre, along that normal.
  const Eigen::Vector3d& centre = face.nominal.origin_mm;
  const double along = face.normal.dot(nominal);
  face.plane_offset_mm = std::abs(along) > 1e-12 ? face.normal.dot(fit.point - centre) / along : 0.0;
  set_form_about(points, "least-squares plane", options, face,
                 [&](const Eigen::Vector3d& p) { return face.normal.dot(p - fit.point); });
}

void measure_cylinder(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                      const InspectOptions& options, FaceInspection& face) {
  const CadFace& nominal = face.nominal;
  CylinderFitOptions fit_options;
  fit_options.axis_prior = nominal.axis;
  fit_options.min_radius_mm = 0.5 * nominal.radius_mm;
  fit_options.max_radius_mm = 2.0 * nominal.radius_mm;
  CylinderFitResult fit;
  try {
    fit = fit_cylinder(points, normals, fit_options);
  } catch (const Error& e) {  // degenerate points (all on a line, coincident): no cylinder to fit
    face.fit_note = std::string("cylinder fit: ") + e.what();
    return;
  }
  if (!fit.ok) {
    face.fit_note = "cylinder fit: " + fit.termination;
    return;
  }
  const Cylinder& c = fit.cylinder;
  face.fitted = true;
  face.radius_mm = c.radius_mm;
  face.radius_std_mm = fit.radius_std_mm;
  face.axis = c.axis_direction.dot(nominal.axis) >= 0.0 ? c.axis_direction : Eigen::Vector3d(-c.axis_direction);
  face.axis_angle_deg = angle_deg(face.axis, nominal.axis);
  // The nominal axis point at the face's middle, and the fitted axis's point nearest it.
  const Eigen::Vector3d v = nominal.origin_mm - c.axis_point;
  face.axis_point_mm = c.axis_point + v.dot(face.axis) * face.axis;
  face.axis_offset_mm = (nominal.origin_mm - face.axis_point_mm).norm();
  // The fitted axis over the points' span, and its ends' distances from the nominal axis.
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const Eigen::Vector3d& p : points) {
    const double h = (p - face.axis_point_mm).dot(face.axis);
    low = std::min(low, h);
    high = std::max(high, h);
  }
  face.length_mm = high - low;
  double farthest = 0.0;
  for (const double h : {low, high}) {
    const Eigen::Vector3d end = face.axis_point_mm + h * face.axis;
    const Eigen::Vector3d from_nominal = end - nominal.origin_mm;
    farthest = std::max(farthest, (from_nominal - from_nominal.dot(nominal.axis) * nominal.axis).norm());
  }
  face.position_mm = 2.0 * farthest;
  set_form_about(points, "least-squares cylinder", options, face,
                 [&](const Eigen::Vector3d& p) { return signed_distance(c, p); });
}

void measure_sphere(const std::vector<Eigen::Vector3d>& points, const InspectOptions& options, FaceInspection& face) {
  const SphereFit fit = fit_sphere(points);
  if (!fit.ok) {
    face.fit_note = "sphere fit: the points do not determine a sphere (on a plane or a circle, or no convergence)";
    return;
  }
  face.fitted = true;
  face.radius_mm = fit.radius_mm;
  face.centre_mm = fit.centre;
  face.centre_offset_mm = (fit.centre - face.nominal.origin_mm).norm();
  set_form_about(points, "least-squares sphere", options, face,
                 [&](const Eigen::Vector3d& p) { return (p - fit.centre).norm() - fit.radius_mm; });
}

// The least-squares cone from the nominal (fitting/revolved.h): its half-angle, axis, apex, and at the
// nominal's middle section (the nominal axis point nearest the face's centre) the axis offset and both radii.
void measure_cone(const std::vector<Eigen::Vector3d>& points, const InspectOptions& options, FaceInspection& face) {
  const CadFace& nominal = face.nominal;
  const ConeFit fit = fit_cone(points, nominal.origin_mm, nominal.axis, nominal.half_angle_rad);
  if (!fit.ok) {
    face.fit_note = "cone fit: the points do not determine a cone (too narrow a band, or no convergence)";
    return;
  }
  face.fitted = true;
  face.axis = fit.axis;
  face.axis_angle_deg = angle_deg(fit.axis, nominal.axis);
  face.half_angle_deg = degrees(fit.half_angle_rad);
  face.apex_mm = fit.apex;
  const Eigen::Vector3d middle = nominal.origin_mm + (nominal.centre_mm - nominal.origin_mm).dot(nominal.axis) *
                                                         nominal.axis;
  const double along = (middle - fit.axis_point).dot(fit.axis);
  face.axis_point_mm = fit.axis_point + along * fit.axis;
  face.axis_offset_mm = (middle - face.axis_point_mm).norm();
  face.radius_mm = fit.radius_mm + along * std::tan(fit.half_angle_rad);
  face.nominal_radius_mm = (middle - nominal.origin_mm).norm() * std::tan(nominal.half_angle_rad);
  set_form_about(points, "least-squares cone", options, face,
                 [&](const Eigen::Vector3d& p) { return cone_distance(fit, p); });
}

void measure_torus(const std::vector<Eigen::Vector3d>& points, const InspectOptions& options, FaceInspection& face) {
  const CadFace& nominal = face.nominal;
  const TorusFit fit =
      fit_torus(points, nominal.origin_mm, nominal.axis, nominal.radius_mm, nominal.minor_radius_mm);
  if (!fit.ok) {
    face.fit_note = "torus fit: the points do not determine a torus (too small a patch, or no convergence)";
    return;
  }
  face.fitted = true;
  face.axis = fit.axis.dot(nominal.axis) >= 0.0 ? fit.axis : Eigen::Vector3d(-fit.axis);
  face.axis_angle_deg = angle_deg(face.axis, nominal.axis);
  face.centre_mm = fit.centre;
  face.centre_offset_mm = (fit.centre - nominal.origin_mm).norm();
  face.radius_mm = fit.major_radius_mm;
  face.minor_radius_mm = fit.minor_radius_mm;
  set_form_about(points, "least-squares torus", options, face,
                 [&](const Eigen::Vector3d& p) { return torus_distance(fit, p); });
}

}  // namespace

void measure_face(const std::vector<Eigen::Vector3d>& points, const std::vector<Eigen::Vector3d>& normals,
                  const std::vector<double>& deviation_mm, const InspectOptions& options, FaceInspection& face) {
  face.points = points.size();
  face.exact = is_analytic(face.nominal.type);
  face.nominal_radius_mm = face.nominal.radius_mm;
  face.deviation = deviation_statistics(deviation_mm);
  if (points.empty()) return;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  face.centroid_mm = sum / static_cast<double>(points.size());
  if (points.size() < options.min_fit_points) {
    face.fit_note = "fewer than " + std::to_string(options.min_fit_points) + " points";
    return;
  }
  if (face.nominal.type == CadSurfaceType::kPlane) measure_plane(points, options, face);
  if (face.nominal.type == CadSurfaceType::kCylinder) measure_cylinder(points, normals, options, face);
  if (face.nominal.type == CadSurfaceType::kSphere) measure_sphere(points, options, face);
  if (face.nominal.type == CadSurfaceType::kCone) measure_cone(points, options, face);
  if (face.nominal.type == CadSurfaceType::kTorus) measure_torus(points, options, face);
  if (!face.form_measured) {
    // No feature fitted (another surface, or the fit failed): the zone of the deviations from the nominal surface,
    // which holds the feature's size and position errors as well as its form.
    face.form_measured = true;
    face.form_reference = "nominal surface";
    face.form = form_zone(deviation_mm, options.form_trim);
    if (face.fit_note.empty()) face.fit_note = std::string("no fit for a ") + to_string(face.nominal.type);
  }
}

}  // namespace conform::detail
