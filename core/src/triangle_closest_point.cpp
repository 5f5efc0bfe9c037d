// The closest point of a triangle to a point: Ericson, Real-Time Collision Detection (2005), 5.1.5, which tests the
// Voronoi regions of the vertices, then the edges, then the face. A triangle without area (collinear or coincident
// vertices) has no face region: its closest point is the closest point on its three edges.

#include <algorithm>

#include "conform/core/triangle_index.h"

namespace conform {
namespace {

SurfacePoint make(const Eigen::Vector3d& p, const Eigen::Vector3d& point, double wa, double wb, double wc,
                  TriangleFeature feature) {
  SurfacePoint s;
  s.point = point;
  s.barycentric = Eigen::Vector3d(wa, wb, wc);
  s.feature = feature;
  s.sq_distance = (p - point).squaredNorm();
  return s;
}

// Closest point on segment (u, v), as the parameter t in [0, 1] of u + t (v - u); 0 for a zero-length segment.
double segment_parameter(const Eigen::Vector3d& p, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const Eigen::Vector3d d = v - u;
  const double len2 = d.squaredNorm();
  if (!(len2 > 0.0)) return 0.0;
  return std::clamp((p - u).dot(d) / len2, 0.0, 1.0);
}

// A triangle without area: the best of its three edges (vertex features at the ends of each edge). Edges are tried
// in the order 01, 12, 20 and a later one wins only when strictly closer, so the answer is deterministic.
SurfacePoint closest_on_edges(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
  struct Edge {
    const Eigen::Vector3d& u;
    const Eigen::Vector3d& v;
    int iu, iv;
    TriangleFeature edge, at_u, at_v;
  };
  const Edge edges[3] = {
      {a, b, 0, 1, TriangleFeature::kEdge01, TriangleFeature::kVertex0, TriangleFeature::kVertex1},
      {b, c, 1, 2, TriangleFeature::kEdge12, TriangleFeature::kVertex1, TriangleFeature::kVertex2},
      {c, a, 2, 0, TriangleFeature::kEdge20, TriangleFeature::kVertex2, TriangleFeature::kVertex0},
  };
  SurfacePoint best;
  for (const Edge& e : edges) {
    const double t = segment_parameter(p, e.u, e.v);
    double w[3] = {0.0, 0.0, 0.0};
    w[e.iu] = 1.0 - t;
    w[e.iv] += t;  // += so that a face with two equal vertex indices still sums to one
    const TriangleFeature feature = t <= 0.0 ? e.at_u : (t >= 1.0 ? e.at_v : e.edge);
    const Eigen::Vector3d point = t <= 0.0 ? e.u : (t >= 1.0 ? e.v : Eigen::Vector3d(e.u + t * (e.v - e.u)));
    const SurfacePoint candidate = make(p, point, w[0], w[1], w[2], feature);
    if (candidate.sq_distance < best.sq_distance) best = candidate;
  }
  return best;
}

// A triangle whose doubled area |ab x ac| is below 1e-12 of the square on its longest edge is treated as having no
// area: the face region's denominator (va + vb + vc = |ab x ac|^2) would be rounding noise.
constexpr double kDegenerateRelativeArea2 = 1e-24;

bool degenerate(const Eigen::Vector3d& ab, const Eigen::Vector3d& ac) {
  const double longest2 = std::max({ab.squaredNorm(), ac.squaredNorm(), (ac - ab).squaredNorm()});
  return !(ab.cross(ac).squaredNorm() > kDegenerateRelativeArea2 * longest2 * longest2);
}

}  // namespace

SurfacePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a;
  const Eigen::Vector3d ac = c - a;
  if (degenerate(ab, ac)) return closest_on_edges(p, a, b, c);

  const Eigen::Vector3d ap = p - a;
  const double d1 = ab.dot(ap);
  const double d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return make(p, a, 1.0, 0.0, 0.0, TriangleFeature::kVertex0);

  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp);
  const double d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return make(p, b, 0.0, 1.0, 0.0, TriangleFeature::kVertex1);

  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return make(p, a + v * ab, 1.0 - v, v, 0.0, TriangleFeature::kEdge01);
  }

  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp);
  const double d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return make(p, c, 0.0, 0.0, 1.0, TriangleFeature::kVertex2);

  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return make(p, a + w * ac, 1.0 - w, 0.0, w, TriangleFeature::kEdge20);
  }

  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return make(p, b + w * (c - b), 0.0, 1.0 - w, w, TriangleFeature::kEdge12);
  }

  // Inside the face: barycentric coordinates from the ratios of the signed areas va, vb, vc.
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom;
  const double w = vc * denom;
  return make(p, a + ab * v + ac * w, 1.0 - v - w, v, w, TriangleFeature::kFace);
}

}  // namespace conform
