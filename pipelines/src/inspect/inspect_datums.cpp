#include "inspect/inspect_datums.h"

#include <cmath>

#include "conform/core/error.h"
#include "conform/evaluation/form.h"

namespace conform::detail {

namespace {

constexpr double kMinSine = 0.17364817766693033;  // sin 10 deg

struct Plane {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;  // outward, like the nominal
};

std::string name_of(std::size_t k, std::size_t face_id) {
  static const char* const kNames[] = {"primary", "secondary", "tertiary"};
  return std::string("the ") + kNames[k] + " datum (face " + std::to_string(face_id) + ")";
}

// The datum's least-squares plane in the frame after T.
Plane fitted_plane(const DatumInput& d, std::size_t k, const Eigen::Isometry3d& T) {
  if (d.nominal.type != CadSurfaceType::kPlane) {
    throw Error(name_of(k, d.face_id) + " is a " + to_string(d.nominal.type) + ": datums are planes");
  }
  std::vector<Eigen::Vector3d> moved;
  moved.reserve(d.points.size());
  for (const Eigen::Vector3d& p : d.points) moved.push_back(T * p);
  const PlaneFit fit = fit_plane(moved);
  if (!fit.ok) {
    throw Error(name_of(k, d.face_id) + " has " + std::to_string(d.points.size()) +
                " scan points, too few (or on a line) to fit its plane");
  }
  return {fit.point, fit.normal.dot(d.nominal.axis) >= 0.0 ? fit.normal : Eigen::Vector3d(-fit.normal)};
}

// x -> R (x - centre) + centre + shift.
Eigen::Isometry3d about(const Eigen::Matrix3d& R, const Eigen::Vector3d& centre, const Eigen::Vector3d& shift) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = centre - R * centre + shift;
  return T;
}

}  // namespace

DatumFit fit_datums(const std::vector<DatumInput>& datums) {
  if (datums.empty() || datums.size() > 3) throw Error("--datums takes 1 to 3 faces");
  DatumFit out;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // Primary: its plane onto the nominal (the rotation taking the fitted normal to the nominal, about its centroid).
  const Eigen::Vector3d nA = datums[0].nominal.axis;
  const Plane a = fitted_plane(datums[0], 0, T);
  const Eigen::Matrix3d Ra = Eigen::Quaterniond::FromTwoVectors(a.normal, nA).toRotationMatrix();
  const double ta = nA.dot(datums[0].nominal.origin_mm - a.point);
  T = about(Ra, a.point, ta * nA) * T;
  out.moved_mm.push_back(ta);
  if (datums.size() == 1) {
    out.T_datum_initial = T;
    return out;
  }
  // Secondary: turned about the primary's normal (through its centroid) until its normal, seen along the primary's
  // normal, is the nominal's; then moved across the primary's normal onto its nominal plane.
  const Eigen::Vector3d nB = datums[1].nominal.axis;
  const Eigen::Vector3d w = (nB - nB.dot(nA) * nA);
  if (w.norm() < kMinSine) throw Error(name_of(1, datums[1].face_id) + " is parallel to the primary datum's plane");
  const Plane b = fitted_plane(datums[1], 1, T);
  const Eigen::Vector3d u = (b.normal - b.normal.dot(nA) * nA).normalized();
  const Eigen::Vector3d wn = w.normalized();
  const double angle = std::atan2(u.cross(wn).dot(nA), u.dot(wn));
  const Eigen::Matrix3d Rb = Eigen::AngleAxisd(angle, nA).toRotationMatrix();
  const double tb = nB.dot(datums[1].nominal.origin_mm - b.point) / nB.dot(wn);
  T = about(Rb, b.point, tb * wn) * T;
  out.moved_mm.push_back(tb * nB.dot(wn));
  if (datums.size() == 2) {
    out.T_datum_initial = T;
    return out;
  }
  // Tertiary: moved along the line the first two leave free.
  const Eigen::Vector3d d = nA.cross(wn).normalized();
  const Eigen::Vector3d nC = datums[2].nominal.axis;
  if (std::abs(nC.dot(d)) < kMinSine) {
    throw Error(name_of(2, datums[2].face_id) + " does not fix the direction the primary and secondary leave free");
  }
  const Plane c = fitted_plane(datums[2], 2, T);
  const double tc = nC.dot(datums[2].nominal.origin_mm - c.point) / nC.dot(d);
  Eigen::Isometry3d shift = Eigen::Isometry3d::Identity();
  shift.translation() = tc * d;
  T = shift * T;
  out.moved_mm.push_back(tc * nC.dot(d));
  out.T_datum_initial = T;
  return out;
}

}  // namespace conform::detail
