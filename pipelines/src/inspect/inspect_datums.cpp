#include "inspect/inspect_datums.h"

#include <cmath>

#include "conform/core/error.h"
#include "conform/evaluation/form.h"
#include "conform/fitting/cylinder.h"

namespace conform::detail {

namespace {

constexpr double kMinSine = 0.17364817766693033;    // sin 10 deg
constexpr double kMinCosine = 0.984807753012208;    // cos 10 deg
constexpr char kSupported[] =
    " (supported: a plane primary; then a plane or a cylinder square to it; then a plane or a cylinder)";

struct Plane {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;  // outward, like the nominal
};

struct Axis {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;  // like the nominal's
};

std::string name_of(std::size_t k, std::size_t face_id) {
  static const char* const kNames[] = {"primary", "secondary", "tertiary"};
  return std::string("the ") + kNames[k] + " datum (face " + std::to_string(face_id) + ")";
}

std::vector<Eigen::Vector3d> moved_points(const DatumInput& d, const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(d.points.size());
  for (const Eigen::Vector3d& p : d.points) out.push_back(T * p);
  return out;
}

// The datum's least-squares plane in the frame after T.
Plane fitted_plane(const DatumInput& d, std::size_t k, const Eigen::Isometry3d& T) {
  const PlaneFit fit = fit_plane(moved_points(d, T));
  if (!fit.ok) {
    throw Error(name_of(k, d.face_id) + " has " + std::to_string(d.points.size()) +
                " scan points, too few (or on a line) to fit its plane");
  }
  return {fit.point, fit.normal.dot(d.nominal.axis) >= 0.0 ? fit.normal : Eigen::Vector3d(-fit.normal)};
}

// The datum's cylinder axis in the frame after T (fitting/cylinder.h, the nominal axis as prior).
Axis fitted_axis(const DatumInput& d, std::size_t k, const Eigen::Isometry3d& T) {
  std::vector<Eigen::Vector3d> normals;
  normals.reserve(d.normals.size());
  for (const Eigen::Vector3d& n : d.normals) normals.push_back(T.linear() * n);
  CylinderFitOptions options;
  options.axis_prior = d.nominal.axis;
  options.min_radius_mm = 0.5 * d.nominal.radius_mm;
  options.max_radius_mm = 2.0 * d.nominal.radius_mm;
  CylinderFitResult fit;
  try {
    if (d.points.size() < 6) throw Error("fewer than 6 points");
    fit = fit_cylinder(moved_points(d, T), normals, options);
  } catch (const Error& e) {
    throw Error(name_of(k, d.face_id) + ": no cylinder to fit on its " + std::to_string(d.points.size()) +
                " scan points: " + e.what());
  }
  if (!fit.ok) throw Error(name_of(k, d.face_id) + ": its cylinder fit failed: " + fit.termination);
  const Eigen::Vector3d a = fit.cylinder.axis_direction;
  return {fit.cylinder.axis_point, a.dot(d.nominal.axis) >= 0.0 ? a : Eigen::Vector3d(-a)};
}

// The point where the axis crosses the plane through `at` perpendicular to n (the axis is not parallel to it).
Eigen::Vector3d crossing(const Axis& axis, const Eigen::Vector3d& at, const Eigen::Vector3d& n) {
  return axis.point + (at - axis.point).dot(n) / axis.direction.dot(n) * axis.direction;
}

Eigen::Vector3d across(const Eigen::Vector3d& v, const Eigen::Vector3d& n) { return v - v.dot(n) * n; }

// x -> R (x - centre) + centre + shift.
Eigen::Isometry3d about(const Eigen::Matrix3d& R, const Eigen::Vector3d& centre, const Eigen::Vector3d& shift) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = centre - R * centre + shift;
  return T;
}

Eigen::Isometry3d shifted(const Eigen::Vector3d& shift) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = shift;
  return T;
}

// The angle about n from u to w (both seen along n).
double angle_about(const Eigen::Vector3d& u, const Eigen::Vector3d& w, const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = across(u, n).normalized(), b = across(w, n).normalized();
  return std::atan2(a.cross(b).dot(n), a.dot(b));
}

bool is_cylinder(const DatumInput& d) { return d.nominal.type == CadSurfaceType::kCylinder; }

void check_type(const DatumInput& d, std::size_t k) {
  const bool plane = d.nominal.type == CadSurfaceType::kPlane;
  if (plane || (k > 0 && is_cylinder(d))) return;
  throw Error(name_of(k, d.face_id) + " is a " + to_string(d.nominal.type) + ": " +
              (k == 0 ? "the primary datum must be a plane" : "datums are planes and cylinders") + kSupported);
}

// The secondary and tertiary when B is a plane: B turned about nA and moved across it; C moved along the free line.
void plane_then(const std::vector<DatumInput>& datums, Eigen::Isometry3d& T, DatumFit& out) {
  const Eigen::Vector3d nA = datums[0].nominal.axis, nB = datums[1].nominal.axis;
  const Eigen::Vector3d w = across(nB, nA);
  if (w.norm() < kMinSine) throw Error(name_of(1, datums[1].face_id) + " is parallel to the primary datum's plane");
  const Eigen::Vector3d wn = w.normalized();
  const Plane b = fitted_plane(datums[1], 1, T);
  const Eigen::Matrix3d Rb = Eigen::AngleAxisd(angle_about(b.normal, wn, nA), nA).toRotationMatrix();
  const double tb = nB.dot(datums[1].nominal.origin_mm - b.point) / nB.dot(wn);
  T = about(Rb, b.point, tb * wn) * T;
  out.moved_mm.push_back(tb * nB.dot(wn));
  if (datums.size() == 2) return;
  const Eigen::Vector3d d = nA.cross(wn).normalized();  // the free line
  const DatumInput& c = datums[2];
  double t = 0.0;
  if (is_cylinder(c)) {
    // The axis moves by the part of the shift across it: t d_perp must take the fitted axis onto the nominal one.
    const Eigen::Vector3d d_perp = across(d, c.nominal.axis);
    if (d_perp.norm() < kMinSine) {
      throw Error(name_of(2, c.face_id) + "'s axis runs along the line the primary and secondary leave free" +
                  kSupported);
    }
    const Axis axis = fitted_axis(c, 2, T);
    const Eigen::Vector3d o = c.nominal.origin_mm;
    const Eigen::Vector3d q = axis.point + (o - axis.point).dot(axis.direction) * axis.direction;
    t = (o - q).dot(d_perp) / d_perp.squaredNorm();
    out.moved_mm.push_back(std::abs(t) * d_perp.norm());
  } else {
    const Eigen::Vector3d nC = c.nominal.axis;
    if (std::abs(nC.dot(d)) < kMinSine) {
      throw Error(name_of(2, c.face_id) + " does not fix the direction the primary and secondary leave free");
    }
    const Plane p = fitted_plane(c, 2, T);
    t = nC.dot(c.nominal.origin_mm - p.point) / nC.dot(d);
    out.moved_mm.push_back(t * nC.dot(d));
  }
  T = shifted(t * d) * T;
}

// The secondary and tertiary when B is a cylinder square to A: B's axis moved across nA onto the nominal; C turns the
// part about B's nominal axis.
void cylinder_then(const std::vector<DatumInput>& datums, Eigen::Isometry3d& T, DatumFit& out) {
  const Eigen::Vector3d nA = datums[0].nominal.axis;
  const DatumInput& b = datums[1];
  if (std::abs(b.nominal.axis.dot(nA)) < kMinCosine) {
    throw Error(name_of(1, b.face_id) + " is a cylinder whose axis is not square to the primary datum's plane" +
                kSupported);
  }
  const Eigen::Vector3d oB = b.nominal.origin_mm;
  const Eigen::Vector3d shift = across(oB - crossing(fitted_axis(b, 1, T), oB, nA), nA);
  T = shifted(shift) * T;
  out.moved_mm.push_back(shift.norm());
  if (datums.size() == 2) return;
  const DatumInput& c = datums[2];
  double angle = 0.0;
  std::vector<Eigen::Vector3d> points = moved_points(c, T);
  if (is_cylinder(c)) {
    const Eigen::Vector3d oC = c.nominal.origin_mm;
    const Eigen::Vector3d nominal = across(oC - oB, nA);
    if (nominal.norm() < 1.0 || std::abs(c.nominal.axis.dot(nA)) < kMinCosine) {
      throw Error(name_of(2, c.face_id) + " is a cylinder not square to the primary datum or within 1 mm of the " +
                  "secondary's axis: it does not fix the turn about it" + kSupported);
    }
    angle = angle_about(crossing(fitted_axis(c, 2, T), oC, nA) - oB, nominal, nA);
  } else {
    const Eigen::Vector3d nC = c.nominal.axis;
    if (across(nC, nA).norm() < kMinSine) {
      throw Error(name_of(2, c.face_id) + " is parallel to the primary datum's plane: it does not fix the turn " +
                  "about the secondary's axis" + kSupported);
    }
    angle = angle_about(fitted_plane(c, 2, T).normal, nC, nA);
  }
  const Eigen::Isometry3d turn = about(Eigen::AngleAxisd(angle, nA).toRotationMatrix(), oB, Eigen::Vector3d::Zero());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centroid += p;
  if (!points.empty()) centroid /= static_cast<double>(points.size());
  out.moved_mm.push_back((turn * centroid - centroid).norm());
  T = turn * T;
}

}  // namespace

DatumFit fit_datums(const std::vector<DatumInput>& datums) {
  if (datums.empty() || datums.size() > 3) throw Error("--datums takes 1 to 3 faces");
  for (std::size_t k = 0; k < datums.size(); ++k) check_type(datums[k], k);
  DatumFit out;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // Primary: its plane onto the nominal (the rotation taking the fitted normal to the nominal, about its centroid).
  const Eigen::Vector3d nA = datums[0].nominal.axis;
  const Plane a = fitted_plane(datums[0], 0, T);
  const Eigen::Matrix3d Ra = Eigen::Quaterniond::FromTwoVectors(a.normal, nA).toRotationMatrix();
  const double ta = nA.dot(datums[0].nominal.origin_mm - a.point);
  T = about(Ra, a.point, ta * nA) * T;
  out.moved_mm.push_back(ta);
  if (datums.size() > 1) {
    if (is_cylinder(datums[1])) {
      cylinder_then(datums, T, out);
    } else {
      plane_then(datums, T, out);
    }
  }
  out.T_datum_initial = T;
  return out;
}

}  // namespace conform::detail
