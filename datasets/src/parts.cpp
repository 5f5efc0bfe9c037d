#include "conform/datasets/parts.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "conform/core/error.h"
#include "conform/core/random.h"

namespace conform {

namespace {

using Vec = Eigen::Vector3d;

// Guard against a mistyped edge length exhausting memory (the box has ~1.1e5 mm^2 of surface).
constexpr double kMaxTriangles = 20e6;
constexpr double kBoxArea = 2.0 * 5150.0 + 80.0 * 540.0 + 4.0 * 600.0;  // caps, extruded profile, boss (upper bound)
constexpr double kFreeformArea = 200.0 * 150.0 * 1.3;                   // the plan area times a slope allowance

// (1 - t) a + t b, keeping a coordinate that a and b share exact (so that the grids of two facets meet on their
// common edge, and an axis-aligned facet stays in its plane to the last bit).
Vec lerp(const Vec& a, const Vec& b, double t) {
  Vec p = (1.0 - t) * a + t * b;
  for (int k = 0; k < 3; ++k) {
    if (a(k) == b(k)) p(k) = a(k);
  }
  return p;
}

// Builds a mesh from facets, welding vertices that coincide to 1 nm (facets meet along shared edges).
class MeshBuilder {
 public:
  std::int32_t vertex(const Vec& p) {
    const std::array<long long, 3> key{std::llround(p.x() * 1e6), std::llround(p.y() * 1e6), std::llround(p.z() * 1e6)};
    const auto [it, added] = index_.emplace(key, static_cast<std::int32_t>(mesh_.vertices.size()));
    if (added) mesh_.vertices.push_back(p);
    return it->second;
  }
  void face(std::int32_t a, std::int32_t b, std::int32_t c) { mesh_.faces.push_back({a, b, c}); }

  // A planar convex quadrilateral a b c d, counter-clockwise seen from outside, on a bilinear grid whose cells are
  // at most edge_mm on a side.
  void quad(const Vec& a, const Vec& b, const Vec& c, const Vec& d, double edge_mm) {
    const int nu = std::max(1, static_cast<int>(std::ceil(std::max((b - a).norm(), (c - d).norm()) / edge_mm)));
    const int nv = std::max(1, static_cast<int>(std::ceil(std::max((d - a).norm(), (c - b).norm()) / edge_mm)));
    std::vector<std::int32_t> ids(static_cast<std::size_t>((nu + 1) * (nv + 1)));
    for (int j = 0; j <= nv; ++j) {
      const double v = static_cast<double>(j) / nv;
      for (int i = 0; i <= nu; ++i) {
        const double u = static_cast<double>(i) / nu;
        const Vec p = lerp(lerp(a, b, u), lerp(d, c, u), v);
        ids[static_cast<std::size_t>(j * (nu + 1) + i)] = vertex(p);
      }
    }
    grid_faces(ids, nu, nv);
  }

  // Two triangles per cell of a (nu + 1) x (nv + 1) grid of vertex ids, row by row, split along the shorter
  // diagonal (sheared cells), alternating where both are equally long.
  void grid_faces(const std::vector<std::int32_t>& ids, int nu, int nv) {
    const auto at = [&](int i, int j) { return ids[static_cast<std::size_t>(j * (nu + 1) + i)]; };
    const auto position = [&](std::int32_t id) -> const Vec& { return mesh_.vertices[static_cast<std::size_t>(id)]; };
    for (int j = 0; j < nv; ++j) {
      for (int i = 0; i < nu; ++i) {
        const std::int32_t p00 = at(i, j), p10 = at(i + 1, j), p01 = at(i, j + 1), p11 = at(i + 1, j + 1);
        const double main = (position(p11) - position(p00)).squaredNorm();
        const double anti = (position(p01) - position(p10)).squaredNorm();
        const bool even = (i + j) % 2 == 0;
        if (main < anti * (1.0 - 1e-9) || (even && main <= anti * (1.0 + 1e-9))) {
          face(p00, p10, p11);
          face(p00, p11, p01);
        } else {
          face(p00, p10, p01);
          face(p10, p11, p01);
        }
      }
    }
  }

  Mesh take() { return std::move(mesh_); }

 private:
  Mesh mesh_;
  std::map<std::array<long long, 3>, std::int32_t> index_;
};

// An axis-aligned rectangle of constant z, counter-clockwise seen from +z (up) or from -z.
void flat(MeshBuilder& m, double x0, double x1, double y0, double y1, double z, bool up, double h) {
  if (up) {
    m.quad({x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, h);
  } else {
    m.quad({x0, y0, z}, {x0, y1, z}, {x1, y1, z}, {x1, y0, z}, h);
  }
}

// The extruded profile's side band between profile points p -> q (x, z), for y in [-40, 40]. The profile runs
// counter-clockwise seen from -y, so its outward side is to the right of p -> q seen from -y.
void band(MeshBuilder& m, const Eigen::Vector2d& p, const Eigen::Vector2d& q, double h) {
  constexpr double y0 = -40.0, y1 = 40.0;
  m.quad({p.x(), y0, p.y()}, {p.x(), y1, p.y()}, {q.x(), y1, q.y()}, {q.x(), y0, q.y()}, h);
}

// A convex piece of the profile (x, z corners counter-clockwise in x-z), as the end caps at y = -40 and y = +40.
void caps(MeshBuilder& m, const std::array<Eigen::Vector2d, 4>& c, double h) {
  const auto at = [](const Eigen::Vector2d& p, double y) { return Vec(p.x(), y, p.y()); };
  // Seen from -y (x to the right, z up) the corners run counter-clockwise, so at y = -40 the normal is -y.
  m.quad(at(c[0], -40.0), at(c[1], -40.0), at(c[2], -40.0), at(c[3], -40.0), h);
  m.quad(at(c[0], 40.0), at(c[3], 40.0), at(c[2], 40.0), at(c[1], 40.0), h);
}

void add_noise(Mesh& mesh, const std::vector<Vec>& normals, const PartOptions& options) {
  if (options.noise_mm <= 0.0) return;
  Random random(options.seed);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    mesh.vertices[i] += options.noise_mm * random.normal() * normals[i];
}

void check(const PartOptions& options, double area_mm2) {
  std::string why;
  if (!options.IsValid(&why)) throw Error("part options: " + why);
  if (2.0 * area_mm2 / (options.edge_mm * options.edge_mm) > kMaxTriangles) {  // two per grid cell
    throw Error("part options: edge_mm = " + std::to_string(options.edge_mm) + " would make more than " +
                std::to_string(static_cast<long long>(kMaxTriangles)) + " triangles");
  }
}

}  // namespace

bool PartOptions::IsValid(std::string* error) const {
  std::string why;
  if (!(edge_mm > 0.0) || !std::isfinite(edge_mm)) {
    why = "edge_mm = " + std::to_string(edge_mm) + ": must be finite and > 0";
  } else if (!(noise_mm >= 0.0) || !std::isfinite(noise_mm)) {
    why = "noise_mm = " + std::to_string(noise_mm) + ": must be finite and >= 0";
  }
  if (why.empty()) return true;
  if (error != nullptr) *error = why;
  return false;
}

Mesh box_part(const PartOptions& options) {
  check(options, kBoxArea);
  const double h = options.edge_mm;
  MeshBuilder m;
  using P = Eigen::Vector2d;
  // The profile (x, z), counter-clockwise seen from -y: outward bands to the right of each edge.
  const std::array<P, 7> profile{P(-90, 0), P(90, 0), P(90, 25), P(70, 45), P(20, 45), P(20, 20), P(-90, 20)};
  for (std::size_t i = 0; i < profile.size(); ++i) {
    if (i == 5) continue;  // the low top (20, 20) -> (-90, 20) is cut by the boss: meshed below
    band(m, profile[i], profile[(i + 1) % profile.size()], h);
  }
  caps(m, {P(-90, 0), P(20, 0), P(20, 20), P(-90, 20)}, h);
  caps(m, {P(20, 0), P(90, 0), P(90, 25), P(20, 25)}, h);
  caps(m, {P(20, 25), P(90, 25), P(70, 45), P(20, 45)}, h);
  // The low top, z = 20, x in [-90, 20], around the boss footprint [-70, -30] x [-25, 5].
  flat(m, -90, -70, -40, 40, 20, true, h);
  flat(m, -30, 20, -40, 40, 20, true, h);
  flat(m, -70, -30, -40, -25, 20, true, h);
  flat(m, -70, -30, 5, 40, 20, true, h);
  // The boss: top and four walls.
  flat(m, -70, -30, -25, 5, 35, true, h);
  m.quad({-70, -25, 20}, {-30, -25, 20}, {-30, -25, 35}, {-70, -25, 35}, h);  // -y wall
  m.quad({-30, 5, 20}, {-70, 5, 20}, {-70, 5, 35}, {-30, 5, 35}, h);          // +y wall
  m.quad({-30, -25, 20}, {-30, 5, 20}, {-30, 5, 35}, {-30, -25, 35}, h);      // +x wall
  m.quad({-70, 5, 20}, {-70, -25, 20}, {-70, -25, 35}, {-70, 5, 35}, h);      // -x wall
  Mesh mesh = m.take();
  const std::vector<Vec> normals = vertex_normals_from_faces(mesh);
  add_noise(mesh, normals, options);
  if (options.vertex_normals) mesh.normals = normals;
  return mesh;
}

double freeform_height(double x, double y) {
  const double dome = std::exp(-((x - 35.0) * (x - 35.0) + (y + 20.0) * (y + 20.0)) / 1250.0);
  return 12.0 * std::sin(M_PI * x / 80.0 + 0.3) * std::cos(M_PI * y / 110.0) + 18.0 * dome;
}

Vec freeform_normal(double x, double y) {
  const double dome = std::exp(-((x - 35.0) * (x - 35.0) + (y + 20.0) * (y + 20.0)) / 1250.0);
  const double fx = 12.0 * M_PI / 80.0 * std::cos(M_PI * x / 80.0 + 0.3) * std::cos(M_PI * y / 110.0) -
                    18.0 * dome * 2.0 * (x - 35.0) / 1250.0;
  const double fy = -12.0 * M_PI / 110.0 * std::sin(M_PI * x / 80.0 + 0.3) * std::sin(M_PI * y / 110.0) -
                    18.0 * dome * 2.0 * (y + 20.0) / 1250.0;
  return Vec(-fx, -fy, 1.0).normalized();
}

Mesh freeform_surface(const PartOptions& options) {
  check(options, kFreeformArea);
  const int nu = static_cast<int>(std::ceil(200.0 / options.edge_mm));
  const int nv = static_cast<int>(std::ceil(150.0 / options.edge_mm));
  MeshBuilder m;
  std::vector<std::int32_t> ids;
  std::vector<Vec> normals;
  for (int j = 0; j <= nv; ++j) {
    const double y = -75.0 + 150.0 * j / nv;
    for (int i = 0; i <= nu; ++i) {
      const double x = -100.0 + 200.0 * i / nu;
      ids.push_back(m.vertex({x, y, freeform_height(x, y)}));
      normals.push_back(freeform_normal(x, y));
    }
  }
  m.grid_faces(ids, nu, nv);
  Mesh mesh = m.take();
  add_noise(mesh, normals, options);
  if (options.vertex_normals) mesh.normals = normals;
  return mesh;
}

}  // namespace conform
