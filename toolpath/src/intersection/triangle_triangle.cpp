#include "conform/toolpath/intersection/triangle_triangle.h"

#include <algorithm>
#include <tuple>

#include "conform/toolpath/intersection/exact_orientation.h"

namespace conform {
namespace {

// The symbolic displacement of mesh B, t = eps w1 + eps^2 w2. Generic: no mesh of a scanner has a triangle whose
// plane contains both (the only way all three orders of a decision vanish for a non-degenerate triangle).
const Eigen::Vector3d kW1(0.8191520442889918, 0.3420201433256687, 0.4600650377311522);
const Eigen::Vector3d kW2(-0.2923717047227367, 0.8433914458128857, -0.4510565162951535);
const Eigen::Vector3d kZero = Eigen::Vector3d::Zero();

// Sign of det[q - p, bi + t - p, bj + t - p] = D0 + det[q - p, t, bj - bi]: line p q (mesh A) against edge bi bj
// (mesh B, displaced).
int a_line_b_edge(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& bi,
                  const Eigen::Vector3d& bj) {
  int s = det3_sign(q, p, bi, p, bj, p);
  if (s == 0) s = det3_sign(q, p, kW1, kZero, bj, bi);
  if (s == 0) s = det3_sign(q, p, kW2, kZero, bj, bi);
  return s;
}

// Sign of det[q - p, ai - p - t, aj - p - t] = D0 - det[q - p, t, aj - ai]: line p q (mesh B, displaced) against
// edge ai aj (mesh A).
int b_line_a_edge(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& ai,
                  const Eigen::Vector3d& aj) {
  int s = det3_sign(q, p, ai, p, aj, p);
  if (s == 0) s = -det3_sign(q, p, kW1, kZero, aj, ai);
  if (s == 0) s = -det3_sign(q, p, kW2, kZero, aj, ai);
  return s;
}

}  // namespace

bool EdgeCrossing::key_less(const EdgeCrossing& o) const {
  return std::make_tuple(edge_mesh, v0, v1, triangle) < std::make_tuple(o.edge_mesh, o.v0, o.v1, o.triangle);
}

int side_of_a_point(const IndexedTriangle& b, const Eigen::Vector3d& a) {
  // det[b1 - b0, b2 - b0, a - b0 - t] = D0 - det[b1 - b0, b2 - b0, t]
  int s = orient3d_sign(b.p[0], b.p[1], b.p[2], a);
  if (s == 0) s = -det3_sign(b.p[1], b.p[0], b.p[2], b.p[0], kW1, kZero);
  if (s == 0) s = -det3_sign(b.p[1], b.p[0], b.p[2], b.p[0], kW2, kZero);
  return s;
}

int side_of_b_point(const IndexedTriangle& a, const Eigen::Vector3d& b) {
  // det[a1 - a0, a2 - a0, b + t - a0] = D0 + det[a1 - a0, a2 - a0, t]
  int s = orient3d_sign(a.p[0], a.p[1], a.p[2], b);
  if (s == 0) s = det3_sign(a.p[1], a.p[0], a.p[2], a.p[0], kW1, kZero);
  if (s == 0) s = det3_sign(a.p[1], a.p[0], a.p[2], a.p[0], kW2, kZero);
  return s;
}

bool edge_crosses_triangle(MeshSide edge_mesh, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                           const IndexedTriangle& tri, Eigen::Vector3d* point) {
  const bool a_edge = edge_mesh == MeshSide::kA;
  const int sp = a_edge ? side_of_a_point(tri, p) : side_of_b_point(tri, p);
  const int sq = a_edge ? side_of_a_point(tri, q) : side_of_b_point(tri, q);
  if (sp == 0 || sq == 0 || sp == sq) return false;
  int signs[3];
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& u = tri.p[k];
    const Eigen::Vector3d& v = tri.p[(k + 1) % 3];
    signs[k] = a_edge ? a_line_b_edge(p, q, u, v) : b_line_a_edge(p, q, u, v);
  }
  // The line p q passes through the triangle iff it turns the same way around all three of its edges.
  if (signs[0] == 0 || signs[0] != signs[1] || signs[1] != signs[2]) return false;
  if (point != nullptr) {
    const double dp = orient3d(tri.p[0], tri.p[1], tri.p[2], p);
    const double dq = orient3d(tri.p[0], tri.p[1], tri.p[2], q);
    const double denominator = dp - dq;
    double s = denominator != 0.0 ? dp / denominator : 0.5;
    s = std::clamp(s, 0.0, 1.0);
    *point = p + s * (q - p);
  }
  return true;
}

int intersect_triangles(const IndexedTriangle& a, const IndexedTriangle& b, EdgeCrossing ends[6]) {
  int count = 0;
  const auto test_edges = [&](const IndexedTriangle& own, const IndexedTriangle& other, MeshSide side) {
    for (int k = 0; k < 3; ++k) {
      int i = k;
      int j = (k + 1) % 3;
      // Canonical direction (lower vertex index first), so both triangles sharing the edge compute the same point.
      if (own.index[i] > own.index[j]) std::swap(i, j);
      Eigen::Vector3d point;
      if (!edge_crosses_triangle(side, own.p[i], own.p[j], other, &point)) continue;
      EdgeCrossing& end = ends[count++];
      end.edge_mesh = side;
      end.v0 = own.index[i];
      end.v1 = own.index[j];
      end.triangle = other.face;
      end.point = point;
    }
  };
  // Quick rejection: all of one triangle on one side of the other's plane.
  const int a0 = side_of_a_point(b, a.p[0]);
  if (a0 == side_of_a_point(b, a.p[1]) && a0 == side_of_a_point(b, a.p[2])) return 0;
  const int b0 = side_of_b_point(a, b.p[0]);
  if (b0 == side_of_b_point(a, b.p[1]) && b0 == side_of_b_point(a, b.p[2])) return 0;
  test_edges(a, b, MeshSide::kA);
  test_edges(b, a, MeshSide::kB);
  return count;
}

}  // namespace conform
