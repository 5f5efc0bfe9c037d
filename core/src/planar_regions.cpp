#include "conform/core/planar_regions.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "conform/core/error.h"

namespace conform {

namespace {

// Out-of-plane distance still called coplanar: 1e-5 mm, plus four float roundings of the coordinates (a float STL at
// 5 m from the origin rounds to 0.3 um). A 1 mm strip of a 150 mm radius is 3e-3 mm out of its neighbour's plane.
constexpr double kPlanarAbsoluteMm = 1e-5;
constexpr double kPlanarRelative = 4.0 * 5.96e-8;
constexpr double kSliverShare = 1e-10;

struct Edge {
  std::int32_t a, b;  // a < b
  std::size_t face;
};

const Eigen::Vector3d& vertex(const Mesh& mesh, std::int32_t i) { return mesh.vertices[static_cast<std::size_t>(i)]; }

// Edges sorted by their vertex pair (then face), so that the faces sharing one are adjacent in the list: a counting
// sort by the lower vertex, then each vertex's few edges sorted in place (the order of one full sort, a third of its
// time on a 300k-face mesh).
std::vector<Edge> sorted_edges(const Mesh& mesh) {
  std::vector<std::size_t> start(mesh.vertices.size() + 1, 0);
  for (const Face& face : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = face[static_cast<std::size_t>(k)], j = face[static_cast<std::size_t>((k + 1) % 3)];
      ++start[static_cast<std::size_t>(std::min(i, j)) + 1];
    }
  }
  for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
  std::vector<Edge> edges(3 * mesh.faces.size());
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = mesh.faces[f][static_cast<std::size_t>(k)];
      const std::int32_t j = mesh.faces[f][static_cast<std::size_t>((k + 1) % 3)];
      edges[fill[static_cast<std::size_t>(std::min(i, j))]++] = {std::min(i, j), std::max(i, j), f};
    }
  }
  const auto by_pair = [](const Edge& x, const Edge& y) { return x.b != y.b ? x.b < y.b : x.face < y.face; };
  for (std::size_t v = 0; v + 1 < start.size(); ++v) {
    std::sort(edges.begin() + static_cast<std::ptrdiff_t>(start[v]),
              edges.begin() + static_cast<std::ptrdiff_t>(start[v + 1]), by_pair);
  }
  return edges;
}

// Per face, the faces across its edges (every pair of faces that share an edge, non-manifold edges included), as
// compressed rows: face f's neighbours are neighbour[start[f]] .. neighbour[start[f + 1] - 1], in the order of the
// edges (the regions and widths below do not depend on it).
struct Neighbours {
  std::vector<std::size_t> start, neighbour;
};

// Calls fn(f, g) for every ordered pair of different faces that share an edge.
template <typename Fn>
void for_each_edge_pair(const std::vector<Edge>& edges, Fn&& fn) {
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    for (std::size_t p = i; p < j; ++p) {
      for (std::size_t q = i; q < j; ++q) {
        if (edges[p].face != edges[q].face) fn(edges[p].face, edges[q].face);
      }
    }
    i = j;
  }
}

Neighbours edge_neighbours(const Mesh& mesh, const std::vector<Edge>& edges) {
  Neighbours out;
  out.start.assign(mesh.faces.size() + 1, 0);
  for_each_edge_pair(edges, [&](std::size_t f, std::size_t) { ++out.start[f + 1]; });
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) out.start[f + 1] += out.start[f];
  out.neighbour.resize(out.start.back());
  std::vector<std::size_t> fill(out.start.begin(), out.start.end() - 1);
  for_each_edge_pair(edges, [&](std::size_t f, std::size_t g) { out.neighbour[fill[f]++] = g; });
  return out;
}

// Grows a region from each face not yet taken, largest first (its plane is the best determined), over edges to faces
// whose three vertices lie on the seed's plane. Returns each face's region (faces without area: a region each).
std::vector<std::size_t> grow_regions(const Mesh& mesh, const std::vector<Eigen::Vector3d>& unit_normals,
                                      const std::vector<double>& areas, const Neighbours& neighbours) {
  const std::size_t n = mesh.faces.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return areas[x] > areas[y]; });
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> region(n, kNone);
  std::vector<std::size_t> stack;
  std::size_t next = 0;
  for (std::size_t seed : order) {
    if (region[seed] != kNone) continue;
    const std::size_t id = next++;
    region[seed] = id;
    if (areas[seed] <= 0.0) continue;
    const Eigen::Vector3d& normal = unit_normals[seed];
    const Eigen::Vector3d& origin = vertex(mesh, mesh.faces[seed][0]);
    const auto on_plane = [&](std::size_t g) {
      for (std::int32_t i : mesh.faces[g]) {
        const Eigen::Vector3d& p = vertex(mesh, i);
        const double tolerance = kPlanarAbsoluteMm + kPlanarRelative * p.cwiseAbs().maxCoeff();
        if (std::abs((p - origin).dot(normal)) > tolerance) return false;
      }
      return unit_normals[g].dot(normal) > 0.0;
    };
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t f = stack.back();
      stack.pop_back();
      for (std::size_t k = neighbours.start[f]; k < neighbours.start[f + 1]; ++k) {
        const std::size_t g = neighbours.neighbour[k];
        if (region[g] != kNone || areas[g] <= 0.0 || !on_plane(g)) continue;
        region[g] = id;
        stack.push_back(g);
      }
    }
  }
  return region;
}

// Each region's width: sqrt(12 x) of the middle eigenvalue x of its area-weighted second moment (the width of a
// rectangle exactly; a region is planar, so the smallest eigenvalue is its thickness, ~0).
std::vector<double> region_widths(const Mesh& mesh, const std::vector<double>& areas,
                                  const std::vector<std::size_t>& region, std::size_t count) {
  std::vector<double> area(count, 0.0);
  std::vector<Eigen::Vector3d> first(count, Eigen::Vector3d::Zero());
  std::vector<Eigen::Matrix3d> second(count, Eigen::Matrix3d::Zero());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (areas[f] <= 0.0) continue;
    const std::size_t r = region[f];
    const Eigen::Vector3d a = vertex(mesh, mesh.faces[f][0]), b = vertex(mesh, mesh.faces[f][1]),
                          c = vertex(mesh, mesh.faces[f][2]);
    const Eigen::Vector3d g = (a + b + c) / 3.0;
    // A uniform triangle's covariance about its centroid: the sum of its corners' outer products over 12.
    const Eigen::Matrix3d own =
        ((a - g) * (a - g).transpose() + (b - g) * (b - g).transpose() + (c - g) * (c - g).transpose()) / 12.0;
    area[r] += areas[f];
    first[r] += areas[f] * g;
    second[r] += areas[f] * (own + g * g.transpose());
  }
  std::vector<double> width(count, 0.0);
  for (std::size_t r = 0; r < count; ++r) {
    if (area[r] <= 0.0) continue;
    const Eigen::Vector3d mean = first[r] / area[r];
    const Eigen::Matrix3d covariance = second[r] / area[r] - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance, Eigen::EigenvaluesOnly);
    width[r] = std::sqrt(12.0 * std::max(0.0, eigen.eigenvalues()(1)));
  }
  return width;
}

}  // namespace

std::vector<unsigned char> planar_faces(const Mesh& mesh, double crease_angle_rad) {
  const std::size_t n = mesh.faces.size();
  for (std::size_t f = 0; f < n; ++f) {
    for (std::int32_t i : mesh.faces[f]) {
      if (i < 0 || static_cast<std::size_t>(i) >= mesh.vertices.size()) {
        throw Error("planar faces: face " + std::to_string(f) + " has vertex index " + std::to_string(i) +
                    " out of range");
      }
    }
  }
  std::vector<Eigen::Vector3d> unit_normals(n);
  std::vector<double> areas(n);
  for (std::size_t f = 0; f < n; ++f) {
    unit_normals[f] = face_normal(mesh, f);
    areas[f] = unit_normals[f].isZero() ? 0.0 : face_area(mesh, f);
    // A sliver (area below kSliverShare of its longest edge squared: rounding, not geometry) has no plane of its own.
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, (vertex(mesh, mesh.faces[f][static_cast<std::size_t>(k)]) -
                                   vertex(mesh, mesh.faces[f][static_cast<std::size_t>((k + 1) % 3)]))
                                      .squaredNorm());
    }
    if (areas[f] <= kSliverShare * longest) areas[f] = 0.0;
  }
  const std::vector<Edge> edges = sorted_edges(mesh);
  const Neighbours neighbours = edge_neighbours(mesh, edges);
  const std::vector<std::size_t> region = grow_regions(mesh, unit_normals, areas, neighbours);
  const std::size_t count = n == 0 ? 0 : *std::max_element(region.begin(), region.end()) + 1;
  const std::vector<double> width = region_widths(mesh, areas, region, count);

  std::vector<unsigned char> plane(count, 0);
  // A vertex whose every edge has exactly two faces, both of one region, has its whole fan in that region.
  std::vector<unsigned char> open(mesh.vertices.size(), 0);
  std::vector<std::size_t> fan_region(mesh.vertices.size(), static_cast<std::size_t>(-1));
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].a == edges[i].a && edges[j].b == edges[i].b) ++j;
    const bool inside = j - i == 2 && region[edges[i].face] == region[edges[i + 1].face];
    for (std::int32_t v : {edges[i].a, edges[i].b}) {
      const auto vu = static_cast<std::size_t>(v);
      if (!inside) open[vu] = 1;
      fan_region[vu] = region[edges[i].face];
    }
    i = j;
  }
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    if (!open[v] && fan_region[v] != static_cast<std::size_t>(-1)) plane[fan_region[v]] = 1;
  }
  // The width test against every region met across an edge that is not a crease.
  const double crease_cosine = std::cos(crease_angle_rad);
  std::vector<double> widest_neighbour(count, 0.0);
  for (std::size_t f = 0; f < n; ++f) {
    for (std::size_t k = neighbours.start[f]; k < neighbours.start[f + 1]; ++k) {
      const std::size_t g = neighbours.neighbour[k];
      if (region[g] == region[f] || unit_normals[f].dot(unit_normals[g]) < crease_cosine) continue;
      widest_neighbour[region[f]] = std::max(widest_neighbour[region[f]], width[region[g]]);
    }
  }
  for (std::size_t r = 0; r < count; ++r) {
    if (width[r] > 0.0 && width[r] >= kPlaneWidthRatio * widest_neighbour[r]) plane[r] = 1;
  }
  std::vector<unsigned char> out(n, 0);
  for (std::size_t f = 0; f < n; ++f) out[f] = areas[f] > 0.0 && plane[region[f]] ? 1 : 0;
  return out;
}

}  // namespace conform
