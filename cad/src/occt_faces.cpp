// What a B-rep face is (issue 33): its surface type and, for analytic surfaces, the nominal parameters in the part
// frame, with the side that is outside. BRepAdaptor_Surface applies the face's placement, so the figures are in the
// frame of the tessellation.

#include <cmath>

#include <BRepAdaptor_Surface.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <GProp_GProps.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>

#include "occt_shape.h"

namespace conform::cad {

namespace {

void put(double* out, const gp_XYZ& v) {
  out[0] = v.X();
  out[1] = v.Y();
  out[2] = v.Z();
}

int surface_of(GeomAbs_SurfaceType type) {
  switch (type) {
    case GeomAbs_Plane:
      return CONFORM_CAD_PLANE;
    case GeomAbs_Cylinder:
      return CONFORM_CAD_CYLINDER;
    case GeomAbs_Cone:
      return CONFORM_CAD_CONE;
    case GeomAbs_Sphere:
      return CONFORM_CAD_SPHERE;
    case GeomAbs_Torus:
      return CONFORM_CAD_TORUS;
    case GeomAbs_BezierSurface:
      return CONFORM_CAD_BEZIER;
    case GeomAbs_BSplineSurface:
      return CONFORM_CAD_BSPLINE;
    case GeomAbs_SurfaceOfRevolution:
      return CONFORM_CAD_REVOLUTION;
    case GeomAbs_SurfaceOfExtrusion:
      return CONFORM_CAD_EXTRUSION;
    case GeomAbs_OffsetSurface:
      return CONFORM_CAD_OFFSET;
    default:
      return CONFORM_CAD_OTHER_SURFACE;
  }
}

// The face's outward normal and its point at a parameter inside its bounds (the middle, else a few others where the
// normal is defined: a sphere's pole, a cone's apex). False when none is.
bool outward_normal(const TopoDS_Face& face, const BRepAdaptor_Surface& surface, gp_Pnt* point, gp_Dir* normal) {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  for (const double s : {0.5, 0.3, 0.7, 0.1, 0.9}) {
    const double u = u0 + s * (u1 - u0), v = v0 + (1.0 - s) * (v1 - v0);
    BRepLProp_SLProps props(surface, u, v, 1, 1e-9);
    if (!props.IsNormalDefined()) continue;
    *point = props.Value();
    *normal = props.Normal();
    if (face.Orientation() == TopAbs_REVERSED) normal->Reverse();
    return true;
  }
  return false;
}

int sign_of(double x) { return x >= 0.0 ? 1 : -1; }

// Fills origin, axis, radii and sense of an analytic surface; `p` and `n` a point of the face and its outward normal.
void describe_analytic(const BRepAdaptor_Surface& s, const gp_Pnt& p, const gp_Dir& n, conform_cad_face& f) {
  const gp_XYZ centre(f.centre_mm[0], f.centre_mm[1], f.centre_mm[2]);
  switch (s.GetType()) {
    case GeomAbs_Plane: {
      const gp_Pln plane = s.Plane();
      const gp_XYZ z = plane.Axis().Direction().XYZ();
      const gp_XYZ outward = n.XYZ() * z >= 0.0 ? z : z.Reversed();
      put(f.origin_mm, centre - z * ((centre - plane.Location().XYZ()) * z));
      put(f.axis, outward);
      f.sense = 1;
      break;
    }
    case GeomAbs_Cylinder: {
      const gp_Cylinder c = s.Cylinder();
      const gp_XYZ a = c.Axis().Direction().XYZ(), o = c.Location().XYZ();
      put(f.origin_mm, o + a * ((centre - o) * a));
      put(f.axis, a);
      f.radius_mm = c.Radius();
      const gp_XYZ radial = (p.XYZ() - o) - a * ((p.XYZ() - o) * a);
      f.sense = sign_of(n.XYZ() * radial);
      break;
    }
    case GeomAbs_Cone: {
      const gp_Cone c = s.Cone();
      gp_XYZ a = c.Axis().Direction().XYZ();
      if (c.SemiAngle() < 0.0) a.Reverse();
      const gp_XYZ apex = c.Apex().XYZ();
      put(f.origin_mm, apex);
      put(f.axis, a);
      f.half_angle_rad = std::abs(c.SemiAngle());
      // The gradient of the distance from the cone, rho cos(alpha) - h sin(alpha), points away from the axis.
      const gp_XYZ v = p.XYZ() - apex;
      gp_XYZ radial = v - a * (v * a);
      if (radial.Modulus() > 0.0) radial.Normalize();
      const gp_XYZ gradient = radial * std::cos(f.half_angle_rad) - a * std::sin(f.half_angle_rad);
      f.sense = sign_of(n.XYZ() * gradient);
      break;
    }
    case GeomAbs_Sphere: {
      const gp_Sphere sphere = s.Sphere();
      put(f.origin_mm, sphere.Location().XYZ());
      put(f.axis, gp_XYZ(0, 0, 1));
      f.radius_mm = sphere.Radius();
      f.sense = sign_of(n.XYZ() * (p.XYZ() - sphere.Location().XYZ()));
      break;
    }
    case GeomAbs_Torus: {
      const gp_Torus t = s.Torus();
      const gp_XYZ a = t.Axis().Direction().XYZ(), o = t.Location().XYZ();
      put(f.origin_mm, o);
      put(f.axis, a);
      f.radius_mm = t.MajorRadius();
      f.minor_radius_mm = t.MinorRadius();
      gp_XYZ radial = (p.XYZ() - o) - a * ((p.XYZ() - o) * a);
      if (radial.Modulus() > 0.0) radial.Normalize();
      const gp_XYZ tube_centre = o + radial * t.MajorRadius();
      f.sense = sign_of(n.XYZ() * (p.XYZ() - tube_centre));
      break;
    }
    default:
      break;
  }
}

}  // namespace

conform_cad_face describe_face(const TopoDS_Face& face, std::size_t body) {
  conform_cad_face f{};
  f.body = body;
  f.reversed = face.Orientation() == TopAbs_REVERSED ? 1 : 0;
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props);
  const gp_XYZ centre = props.CentreOfMass().XYZ();
  const bool has_area = std::isfinite(props.Mass()) && props.Mass() > 0.0 && std::isfinite(centre.X()) &&
                        std::isfinite(centre.Y()) && std::isfinite(centre.Z());
  const BRepAdaptor_Surface surface(face);
  f.surface = surface_of(surface.GetType());
  f.axis[2] = 1.0;
  gp_Pnt p;
  gp_Dir n;
  const bool has_normal = outward_normal(face, surface, &p, &n);
  if (has_area) {
    f.area_mm2 = props.Mass();
    put(f.centre_mm, centre);
  } else if (has_normal) {
    put(f.centre_mm, p.XYZ());
  }
  if (f.surface > CONFORM_CAD_TORUS) return f;
  if (!has_normal) {
    f.surface = CONFORM_CAD_OTHER_SURFACE;  // no side to tell outside by: measured as free-form, to its triangles
    return f;
  }
  describe_analytic(surface, p, n, f);
  return f;
}

void turn_inside_out(conform_cad_face& f) {
  f.sense = -f.sense;
  if (f.surface == CONFORM_CAD_PLANE) {
    for (double& a : f.axis) a = -a;
  }
}

}  // namespace conform::cad
