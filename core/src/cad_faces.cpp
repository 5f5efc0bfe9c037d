#include "conform/core/cad_faces.h"

#include "conform/core/constants.h"

#include <cmath>
#include <limits>

namespace conform {

namespace {


// p relative to an axis (origin o, unit a): the height along it and the unit vector away from it (zero on it).
struct AxisFrame {
  double height = 0.0;
  double rho = 0.0;
  Eigen::Vector3d radial = Eigen::Vector3d::Zero();
};

AxisFrame about_axis(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& p) {
  AxisFrame f;
  const Eigen::Vector3d v = p - o;
  f.height = v.dot(a);
  const Eigen::Vector3d r = v - f.height * a;
  f.rho = r.norm();
  if (f.rho > 0.0) f.radial = r / f.rho;
  return f;
}

}  // namespace

const char* to_string(CadSurfaceType type) {
  switch (type) {
    case CadSurfaceType::kPlane:
      return "plane";
    case CadSurfaceType::kCylinder:
      return "cylinder";
    case CadSurfaceType::kCone:
      return "cone";
    case CadSurfaceType::kSphere:
      return "sphere";
    case CadSurfaceType::kTorus:
      return "torus";
    case CadSurfaceType::kBezier:
      return "bezier";
    case CadSurfaceType::kBSpline:
      return "bspline";
    case CadSurfaceType::kRevolution:
      return "revolution";
    case CadSurfaceType::kExtrusion:
      return "extrusion";
    case CadSurfaceType::kOffset:
      return "offset";
    case CadSurfaceType::kOther:
      return "other";
  }
  return "other";
}

bool is_analytic(CadSurfaceType type) {
  return type == CadSurfaceType::kPlane || type == CadSurfaceType::kCylinder || type == CadSurfaceType::kCone ||
         type == CadSurfaceType::kSphere || type == CadSurfaceType::kTorus;
}

double analytic_signed_distance(const CadFace& f, const Eigen::Vector3d& p) {
  const double s = static_cast<double>(f.sense);
  switch (f.type) {
    case CadSurfaceType::kPlane:
      return (p - f.origin_mm).dot(f.axis);
    case CadSurfaceType::kCylinder:
      return s * (about_axis(f.origin_mm, f.axis, p).rho - f.radius_mm);
    case CadSurfaceType::kSphere:
      return s * ((p - f.origin_mm).norm() - f.radius_mm);
    case CadSurfaceType::kCone: {
      const AxisFrame q = about_axis(f.origin_mm, f.axis, p);
      return s * (q.rho * std::cos(f.half_angle_rad) - q.height * std::sin(f.half_angle_rad));
    }
    case CadSurfaceType::kTorus: {
      const AxisFrame q = about_axis(f.origin_mm, f.axis, p);
      return s * (std::hypot(q.rho - f.radius_mm, q.height) - f.minor_radius_mm);
    }
    default:
      return kNaN;
  }
}

Eigen::Vector3d analytic_outward_normal(const CadFace& f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d none = Eigen::Vector3d::Constant(kNaN);
  const double s = static_cast<double>(f.sense);
  switch (f.type) {
    case CadSurfaceType::kPlane:
      return f.axis;
    case CadSurfaceType::kCylinder: {
      const AxisFrame q = about_axis(f.origin_mm, f.axis, p);
      return q.rho > 0.0 ? Eigen::Vector3d(s * q.radial) : none;
    }
    case CadSurfaceType::kSphere: {
      const Eigen::Vector3d v = p - f.origin_mm;
      return v.norm() > 0.0 ? Eigen::Vector3d(s * v.normalized()) : none;
    }
    case CadSurfaceType::kCone: {
      const AxisFrame q = about_axis(f.origin_mm, f.axis, p);
      if (q.rho == 0.0) return none;
      return s * (std::cos(f.half_angle_rad) * q.radial - std::sin(f.half_angle_rad) * f.axis);
    }
    case CadSurfaceType::kTorus: {
      const AxisFrame q = about_axis(f.origin_mm, f.axis, p);
      const Eigen::Vector3d v = (q.rho - f.radius_mm) * q.radial + q.height * f.axis;
      return q.rho > 0.0 && v.norm() > 0.0 ? Eigen::Vector3d(s * v.normalized()) : none;
    }
    default:
      return none;
  }
}

}  // namespace conform
