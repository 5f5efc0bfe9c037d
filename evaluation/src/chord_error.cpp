#include "conform/evaluation/chord_error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "conform/core/error.h"
#include "conform/core/planar_regions.h"

namespace conform {

namespace {

struct Side {
  std::int32_t a, b;
  std::size_t face;
};

// Every face's edges, sorted so that the faces sharing an edge are adjacent.
std::vector<Side> sorted_sides(const Mesh& mesh) {
  std::vector<Side> sides;
  sides.reserve(3 * mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = mesh.faces[f][static_cast<std::size_t>(k)];
      const std::int32_t j = mesh.faces[f][static_cast<std::size_t>((k + 1) % 3)];
      sides.push_back({std::min(i, j), std::max(i, j), f});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.a != y.a ? x.a < y.a : x.b != y.b ? x.b < y.b : x.face < y.face;
  });
  return sides;
}

// Each curved face's estimate replaced by the median over the curved faces that share a vertex with it (itself
// included). A curved surface's faces agree with their neighbours; a scanner mesh's noise bends each edge at random
// (about 0.3 sigma of "sagitta" per face, 1.0 sigma at the tail of 100k faces), and the median keeps the typical
// figure, not the tail.
ChordErrorEstimate neighbourhood_median(const Mesh& mesh, const std::vector<unsigned char>& plane,
                                        const std::vector<double>& raw) {
  const VertexFaces rows = faces_around_vertices(mesh);
  const std::vector<std::size_t>& start = rows.start;
  const std::vector<std::size_t>& around = rows.faces;
  ChordErrorEstimate out;
  out.sagitta_mm.assign(raw.size(), 0.0);
  std::vector<std::size_t> faces;
  std::vector<double> values;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (plane[f]) continue;
    faces.clear();
    for (std::int32_t v : mesh.faces[f]) {
      const auto vu = static_cast<std::size_t>(v);
      faces.insert(faces.end(), around.begin() + static_cast<std::ptrdiff_t>(start[vu]),
                   around.begin() + static_cast<std::ptrdiff_t>(start[vu + 1]));
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    values.clear();
    for (std::size_t g : faces) {
      if (!plane[g]) values.push_back(raw[g]);
    }
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    out.sagitta_mm[f] = *middle;
  }
  return out;
}

}  // namespace

ChordErrorEstimate estimate_chord_error(const Mesh& mesh, double crease_angle_rad) {
  const std::vector<unsigned char> plane = planar_faces(mesh, crease_angle_rad);  // checks the face indices
  std::vector<Eigen::Vector3d> normal(mesh.faces.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) normal[f] = face_normal(mesh, f);
  std::vector<double> raw(mesh.faces.size(), 0.0);
  const std::vector<Side> sides = sorted_sides(mesh);
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].a == sides[i].a && sides[j].b == sides[i].b) ++j;
    const std::size_t f = sides[i].face, g = sides[i + 1 < j ? i + 1 : i].face;
    if (j - i == 2 && !normal[f].isZero() && !normal[g].isZero()) {
      const double bend = std::atan2(normal[f].cross(normal[g]).norm(), normal[f].dot(normal[g]));
      const double edge =
          (mesh.vertices[static_cast<std::size_t>(sides[i].a)] - mesh.vertices[static_cast<std::size_t>(sides[i].b)])
              .norm();
      if (bend < crease_angle_rad && edge > 0.0) {
        for (const std::size_t h : {f, g}) {
          if (plane[h]) continue;
          // The face's height over the shared edge: twice its area over the edge's length.
          const double height = 2.0 * face_area(mesh, h) / edge;
          raw[h] = std::max(raw[h], bend * height / 8.0);
        }
      }
    }
    i = j;
  }
  return neighbourhood_median(mesh, plane, raw);
}

ChordErrorSummary summarize_chord_error(const Mesh& mesh, const ChordErrorEstimate& estimate, double bar_mm) {
  if (estimate.sagitta_mm.size() != mesh.faces.size()) {
    throw Error("chord error: " + std::to_string(estimate.sagitta_mm.size()) + " estimates for " +
                std::to_string(mesh.faces.size()) + " faces");
  }
  ChordErrorSummary s;
  s.bar_mm = bar_mm;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const double area = face_area(mesh, f);
    s.area_mm2 += area;
    s.max_mm = std::max(s.max_mm, estimate.sagitta_mm[f]);
    if (bar_mm > 0.0 && estimate.sagitta_mm[f] >= bar_mm) {
      ++s.faces_over;
      s.area_over_mm2 += area;
    }
  }
  s.max_over_bar = bar_mm > 0.0 ? s.max_mm / bar_mm : 0.0;
  return s;
}

}  // namespace conform
