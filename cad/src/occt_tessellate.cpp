// A shape's bodies into one triangle list: BRepMesh with the requested chordal and angular deflection, placements
// applied, faces wound by their orientation, and each solid's winding checked by the sign of its enclosed volume.

#include <algorithm>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>

#include "occt_progress.h"
#include "occt_shape.h"

namespace conform::cad {

namespace {

struct Body {
  TopoDS_Shape shape;
  int kind = CONFORM_CAD_SOLID;
};

// Solids, then shells outside solids, then faces outside shells (gathered into one body).
std::vector<Body> bodies_of(const TopoDS_Shape& shape) {
  std::vector<Body> bodies;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next()) bodies.push_back({e.Current(), CONFORM_CAD_SOLID});
  for (TopExp_Explorer e(shape, TopAbs_SHELL, TopAbs_SOLID); e.More(); e.Next()) {
    const bool closed = BRep_Tool::IsClosed(e.Current());
    bodies.push_back({e.Current(), closed ? CONFORM_CAD_SOLID : CONFORM_CAD_OPEN_SHELL});
  }
  TopoDS_Compound free_faces;
  BRep_Builder builder;
  builder.MakeCompound(free_faces);
  bool any = false;
  for (TopExp_Explorer e(shape, TopAbs_FACE, TopAbs_SHELL); e.More(); e.Next()) {
    builder.Add(free_faces, e.Current());
    any = true;
  }
  if (any) bodies.push_back({free_faces, CONFORM_CAD_FREE_FACES});
  return bodies;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

// `how`: "would need about" (the estimate, all faces), "would need at least" (the estimate, stopped early), "came to
// more than" (the mesher's own count).
[[noreturn]] void over_budget(double triangles, const char* how, std::size_t max_triangles, double deflection_mm) {
  // Curved faces need triangles in proportion to 1 / deflection (h^2 ~ d R): the deflection that fits, roughly.
  const double fits_mm = deflection_mm * triangles / static_cast<double>(max_triangles) * 1.2;
  throw std::runtime_error("its tessellation at deflection " + number(deflection_mm) + " mm " + how + " " +
                           number(triangles) + " triangles, over the budget of " +
                           std::to_string(max_triangles) + ": use a coarser --cad-deflection (about " +
                           number(fits_mm) + " mm would fit) or raise --cad-max-triangles");
}

// Appends the body's faces to `out`; returns its record (volume from the divergence theorem, about its first vertex).
// Each face is recorded (describe_face) with the triangles it gave.
conform_cad_body add_body(const Body& body, std::size_t body_index, std::size_t max_triangles, double deflection_mm,
                          Tessellation& out) {
  conform_cad_body record{};
  record.kind = body.kind;
  const std::size_t first_vertex = out.vertices.size() / 3;
  const std::size_t first_triangle = out.triangles.size() / 3;
  const std::size_t first_face = out.faces.size();
  for (TopExp_Explorer e(body.shape, TopAbs_FACE); e.More(); e.Next()) {
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    ++record.faces;
    const auto face_index = static_cast<std::int32_t>(out.faces.size());
    out.faces.push_back(describe_face(face, body_index));
    TopLoc_Location location;
    const Handle(Poly_Triangulation) mesh = BRep_Tool::Triangulation(face, location);
    if (mesh.IsNull() || mesh->NbTriangles() == 0) {
      ++record.failed_faces;
      continue;
    }
    const std::size_t so_far = out.triangles.size() / 3 + static_cast<std::size_t>(mesh->NbTriangles());
    if (so_far > max_triangles) {
      over_budget(static_cast<double>(so_far), "came to more than", max_triangles, deflection_mm);
    }
    out.faces.back().triangles = static_cast<std::size_t>(mesh->NbTriangles());
    out.triangle_faces.insert(out.triangle_faces.end(), static_cast<std::size_t>(mesh->NbTriangles()), face_index);
    const gp_Trsf placement = location.Transformation();
    const std::size_t base = out.vertices.size() / 3;
    for (int i = 1; i <= mesh->NbNodes(); ++i) {
      const gp_Pnt p = mesh->Node(i).Transformed(placement);
      out.vertices.insert(out.vertices.end(), {p.X(), p.Y(), p.Z()});
    }
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (int i = 1; i <= mesh->NbTriangles(); ++i) {
      int a = 0, b = 0, c = 0;
      mesh->Triangle(i).Get(a, b, c);
      if (reversed) std::swap(b, c);
      for (int n : {a, b, c}) out.triangles.push_back(static_cast<std::int32_t>(base + static_cast<std::size_t>(n) - 1));
    }
  }
  const std::size_t vertex_end = out.vertices.size() / 3;
  record.triangles = out.triangles.size() / 3 - first_triangle;
  for (int k = 0; k < 3; ++k) {
    record.box_min_mm[k] = std::numeric_limits<double>::infinity();
    record.box_max_mm[k] = -std::numeric_limits<double>::infinity();
  }
  for (std::size_t v = first_vertex; v < vertex_end; ++v) {
    for (int k = 0; k < 3; ++k) {
      record.box_min_mm[k] = std::min(record.box_min_mm[k], out.vertices[3 * v + static_cast<std::size_t>(k)]);
      record.box_max_mm[k] = std::max(record.box_max_mm[k], out.vertices[3 * v + static_cast<std::size_t>(k)]);
    }
  }
  if (record.triangles == 0) return record;
  const double* o = &out.vertices[3 * first_vertex];
  double six_volume = 0.0;
  for (std::size_t t = first_triangle; t < out.triangles.size() / 3; ++t) {
    double p[3][3];
    for (int j = 0; j < 3; ++j) {
      const double* q = &out.vertices[3 * static_cast<std::size_t>(out.triangles[3 * t + static_cast<std::size_t>(j)])];
      for (int k = 0; k < 3; ++k) p[j][k] = q[k] - o[k];
    }
    six_volume += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
                  p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  }
  record.volume_mm3 = six_volume / 6.0;
  if (body.kind == CONFORM_CAD_SOLID && record.volume_mm3 < 0.0) {
    for (std::size_t t = first_triangle; t < out.triangles.size() / 3; ++t) {
      std::swap(out.triangles[3 * t + 1], out.triangles[3 * t + 2]);
    }
    record.volume_mm3 = -record.volume_mm3;
    record.flipped = 1;
    for (std::size_t f = first_face; f < out.faces.size(); ++f) turn_inside_out(out.faces[f]);
  }
  return record;
}

}  // namespace

Tessellation tessellate(const TopoDS_Shape& shape, double deflection_mm, double angular_deflection_rad,
                        std::size_t max_triangles, const ProgressSink& progress) {
  const std::vector<Body> bodies = bodies_of(shape);
  if (bodies.empty()) throw std::runtime_error("it holds no solids, shells or faces (nothing to compare against)");
  progress("tessellate CAD", 0.0);
  const TriangleEstimate estimate = estimate_triangles(shape, deflection_mm, angular_deflection_rad, max_triangles);
  if (!estimate.complete || estimate.triangles > static_cast<double>(max_triangles)) {
    over_budget(estimate.triangles, estimate.complete ? "would need about" : "would need at least", max_triangles,
                deflection_mm);
  }
  IMeshTools_Parameters parameters;
  parameters.Deflection = deflection_mm;
  parameters.Angle = angular_deflection_rad;
  parameters.Relative = Standard_False;
  parameters.InParallel = Standard_False;  // the same bytes on every run
  const Handle(ProgressIndicator) indicator = new ProgressIndicator(progress, "tessellate CAD");
  BRepMesh_IncrementalMesh mesher(shape, parameters, indicator->Start());
  if (!mesher.IsDone()) throw std::runtime_error("the tessellation failed");

  Tessellation out;
  std::size_t faces = 0, failed = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    out.bodies.push_back(add_body(bodies[i], i, max_triangles, deflection_mm, out));
    const conform_cad_body& b = out.bodies.back();
    faces += b.faces;
    failed += b.failed_faces;
    const std::string which = "body " + std::to_string(i + 1);
    if (b.flipped) out.warnings.push_back(which + " (a solid) had its faces pointing inwards; they were reversed");
    if (b.kind == CONFORM_CAD_OPEN_SHELL || b.kind == CONFORM_CAD_FREE_FACES) {
      out.warnings.push_back(which + " is " + (b.kind == CONFORM_CAD_OPEN_SHELL ? "an open shell" : "free faces") +
                             ": not a solid, so the sign of deviations follows its faces' orientation in the file");
    }
  }
  if (faces == 0) throw std::runtime_error("it holds no faces (nothing to compare against)");
  if (failed == faces) {
    throw std::runtime_error("the tessellation failed for every one of its " + std::to_string(faces) + " faces");
  }
  if (failed > 0) {
    out.warnings.push_back(std::to_string(failed) + " of " + std::to_string(faces) +
                           " faces could not be tessellated and are missing from the reference");
  }
  progress("tessellate CAD", 1.0);
  return out;
}

}  // namespace conform::cad
