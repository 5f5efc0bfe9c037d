// How many triangles BRepMesh will make, estimated before it runs (issue 32): a valid 2 KB STEP sphere of radius 10 m
// needs about 20 million triangles at the default 0.005 mm deflection (and gigabytes, for many minutes), and the
// estimate refuses it in milliseconds instead.
//
// A chord of length h on a curve of radius R has the sagitta h^2 / (8 R), so the chordal deflection d allows
// h = sqrt(8 d R); BRepMesh 7.6 checks its triangles' centres and edge midpoints against d and ends up with chords
// about 1.8 times shorter, h = sqrt(2.5 d R) (measured: 222 segments around a cylinder R 15 and 201,196 triangles on
// a sphere R 100, both at 0.005 mm; sqrt(8 d R) would give 122 and 62,832). The angular deflection a allows h = a R;
// the mesher takes the shorter. A face is a grid of such chords along its two principal directions, two triangles
// per cell: about 2 A / (h1 h2) for area A, where a flat direction (a cylinder's axis) spans the face in one cell
// (h = sqrt(A)). The principal curvatures are sampled on a 5 x 5 grid of the face's parameter box and the largest
// taken (the finest grid the mesher needs somewhere on it): a torus is overestimated (tests/cad/cad_isolation_test).
// Not counted: the nodes a face's boundary forces on it (a plane with many holes); the count after meshing is checked
// against the same budget (occt_tessellate.cpp) and the memory limit bounds the rest.

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <BRepAdaptor_Surface.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include "occt_shape.h"

namespace conform::cad {

namespace {

// The largest |principal curvature| in each principal direction over a grid of the face (1/mm; 0 when flat).
void largest_curvatures(const TopoDS_Face& face, double* k_max, double* k_min) {
  *k_max = 0.0;
  *k_min = 0.0;
  BRepAdaptor_Surface surface(face, Standard_False);
  switch (surface.GetType()) {
    case GeomAbs_Plane:
      return;
    case GeomAbs_Cylinder:
      *k_max = 1.0 / surface.Cylinder().Radius();
      return;
    case GeomAbs_Sphere:
      *k_max = *k_min = 1.0 / surface.Sphere().Radius();
      return;
    default:
      break;
  }
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  if (!(std::isfinite(u0) && std::isfinite(u1) && std::isfinite(v0) && std::isfinite(v1))) return;
  constexpr int kSamples = 5;
  BRepLProp_SLProps props(surface, 2, 1e-9);
  for (int i = 0; i < kSamples; ++i) {
    for (int j = 0; j < kSamples; ++j) {
      props.SetParameters(u0 + (u1 - u0) * (i + 0.5) / kSamples, v0 + (v1 - v0) * (j + 0.5) / kSamples);
      if (!props.IsCurvatureDefined()) continue;
      const double a = std::abs(props.MaxCurvature()), b = std::abs(props.MinCurvature());
      *k_max = std::max(*k_max, std::max(a, b));
      *k_min = std::max(*k_min, std::min(a, b));
    }
  }
}

// The chord the mesher allows across curvature k (1/mm), or `flat` where k is 0.
double chord(double k, double deflection_mm, double angle_rad, double flat) {
  if (!(k > 0.0) || !std::isfinite(k)) return flat;
  const double radius = 1.0 / k;
  return std::min({std::sqrt(2.5 * deflection_mm * radius), angle_rad * radius, flat});
}

double face_triangles(const TopoDS_Face& face, double deflection_mm, double angle_rad) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props);
  const double area = std::abs(props.Mass());
  if (!std::isfinite(area)) return 2.0;
  double k_max = 0.0, k_min = 0.0;
  largest_curvatures(face, &k_max, &k_min);
  const double flat = std::max(std::sqrt(area), 1e-9);
  const double h1 = std::max(chord(k_max, deflection_mm, angle_rad, flat), 1e-9);
  const double h2 = std::max(chord(k_min, deflection_mm, angle_rad, flat), 1e-9);
  return std::max(2.0, 2.0 * area / (h1 * h2));
}

}  // namespace

TriangleEstimate estimate_triangles(const TopoDS_Shape& shape, double deflection_mm, double angle_rad,
                                    std::size_t max_triangles) {
  TriangleEstimate out;
  // A face listed many times (a hostile file lists one a million times) is one surface: measured once.
  std::unordered_map<const void*, double> measured;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    const void* key = face.TShape().get();
    auto found = measured.find(key);
    if (found == measured.end()) found = measured.emplace(key, face_triangles(face, deflection_mm, angle_rad)).first;
    out.triangles += found->second;
    out.largest_face = std::max(out.largest_face, found->second);
    ++out.faces;
    // Over the budget already: the rest cannot bring it back (and a million faces need not all be visited).
    if (out.triangles > static_cast<double>(max_triangles)) {
      e.Next();
      out.complete = !e.More();
      break;
    }
  }
  return out;
}

}  // namespace conform::cad
