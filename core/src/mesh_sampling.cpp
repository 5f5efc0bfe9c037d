#include "conform/core/mesh_sampling.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "conform/core/error.h"
#include "conform/core/triangle_index.h"

namespace conform {

namespace {

// Roberts' R3 sequence: x_k = frac(1/2 + k (1/g, 1/g^2, 1/g^3)), g the real root of g^4 = g + 1.
constexpr double kG = 1.2207440846057594753616853491088319144324890862486;
constexpr double kA1 = 1.0 / kG, kA2 = 1.0 / (kG * kG), kA3 = 1.0 / (kG * kG * kG);

double fraction(double x) { return x - std::floor(x); }

// The face of each pick k (the first face whose cumulative area exceeds frac(1/2 + k / g) of the total, the last
// for a pick at the very end): the picks in increasing order, matched in one walk along the faces, instead of a
// binary search per pick that jumps across the whole array (a cache miss per step on a 300k-face mesh). The same
// faces as std::upper_bound gives.
std::vector<std::size_t> faces_picked(const std::vector<double>& cumulative, double total, std::size_t count) {
  std::vector<std::pair<double, std::size_t>> picks(count);
  for (std::size_t k = 0; k < count; ++k) picks[k] = {fraction(0.5 + static_cast<double>(k) * kA1) * total, k};
  std::sort(picks.begin(), picks.end());
  std::vector<std::size_t> face_of(count);
  std::size_t f = 0;
  for (const auto& [pick, k] : picks) {
    while (f + 1 < cumulative.size() && !(cumulative[f] > pick)) ++f;
    face_of[k] = f;
  }
  return face_of;
}

}  // namespace

MeshSurfaceSample sample_mesh_surface(const Mesh& mesh, std::size_t count, const PhongSurface* smooth) {
  if (count == 0) throw Error("surface sample: asked for 0 points");
  check_consistent(mesh, "surface sample");
  std::vector<double> cumulative(mesh.faces.size());
  double total = 0.0;
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Face& t = mesh.faces[f];
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const double area = (mesh.vertices[static_cast<std::size_t>(t[1])] - a)
                            .cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a)
                            .norm();
    total += std::isfinite(area) ? area : 0.0;
    cumulative[f] = total;
  }
  if (!(total > 0.0)) throw Error("surface sample: the mesh has no faces with area");
  const std::vector<std::size_t> face_of = faces_picked(cumulative, total, count);
  MeshSurfaceSample out;
  out.points.reserve(count);
  out.normals.reserve(count);
  out.faces.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double kd = static_cast<double>(k);
    const std::size_t f = face_of[k];
    // Uniform over the triangle's area: the square root of one coordinate spreads the other along the far edge.
    const double r = std::sqrt(fraction(0.5 + kd * kA2)), s = fraction(0.5 + kd * kA3);
    const Face& t = mesh.faces[f];
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    SurfacePoint p;
    p.barycentric = Eigen::Vector3d(1.0 - r, r * (1.0 - s), r * s);
    p.point = p.barycentric[0] * a + p.barycentric[1] * b + p.barycentric[2] * c;
    p.face = static_cast<int>(f);
    p.sq_distance = 0.0;
    Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    if (smooth != nullptr) {
      const PhongPoint lifted = smooth->lift(p);
      p.point = lifted.point;
      if (!lifted.normal.isZero()) normal = lifted.normal;
    }
    out.points.push_back(p.point);
    out.normals.push_back(normal);
    out.faces.push_back(static_cast<std::int32_t>(f));
  }
  return out;
}

}  // namespace conform
