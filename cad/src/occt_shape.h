#pragma once
// The plugin's two steps over OpenCASCADE: read a STEP or IGES file into one shape (placements applied, lengths in
// mm), and tessellate that shape's bodies into one triangle list wound outside-positive.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include "conform/core/cad_plugin_abi.h"

namespace conform::cad {

// Reports to the request's callback (stage, fraction); throttled to steps of 1%.
struct ProgressSink {
  conform_cad_progress_fn fn = nullptr;
  void* context = nullptr;
  void operator()(const char* stage, double fraction) const {
    if (fn != nullptr) fn(context, stage, fraction);
  }
};

struct ReadShape {
  TopoDS_Shape shape;      // every root transferred, as one compound
  std::string file_unit;   // as the file names it
  double mm_per_file_unit = 1.0;
};

// Throws std::runtime_error with the reason (without the path) when the file is not STEP/IGES OpenCASCADE can read
// or holds no geometry.
ReadShape read_shape(const conform_cad_request& request, const ProgressSink& progress);

// BRepMesh's triangle count, estimated before meshing from each face's area and curvature (occt_budget.cpp).
struct TriangleEstimate {
  double triangles = 0.0;     // over the faces visited
  double largest_face = 0.0;  // the most any one face needs
  std::size_t faces = 0;      // faces visited
  bool complete = true;       // false: faces were left once over max_triangles (triangles is then a lower bound)
};
TriangleEstimate estimate_triangles(const TopoDS_Shape& shape, double deflection_mm, double angle_rad,
                                    std::size_t max_triangles);

struct Tessellation {
  std::vector<double> vertices;     // x y z, mm
  std::vector<std::int32_t> triangles;
  std::vector<std::int32_t> triangle_faces;  // per triangle, the index into faces
  std::vector<conform_cad_face> faces;       // every face of every body, in the order visited
  std::vector<conform_cad_body> bodies;
  std::vector<std::string> warnings;
};

// The face's surface type, nominal parameters and outside (occt_faces.cpp); `body` its body's index.
conform_cad_face describe_face(const TopoDS_Face& face, std::size_t body);
// The face of a solid whose triangles were reversed (its faces pointed inwards): outside is the other side.
void turn_inside_out(conform_cad_face& face);

// Throws std::runtime_error when the shape has no faces, no face could be tessellated, or the tessellation is
// estimated (before meshing) or found to need more than max_triangles.
Tessellation tessellate(const TopoDS_Shape& shape, double deflection_mm, double angular_deflection_rad,
                        std::size_t max_triangles, const ProgressSink& progress);

}  // namespace conform::cad
