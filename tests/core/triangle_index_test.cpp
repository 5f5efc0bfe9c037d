#include "conform/core/triangle_index.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "test_meshes.h"

namespace conform {
namespace {

using V = Eigen::Vector3d;

// ---- an independent reference: projection onto the plane if it falls inside, else the nearest of the edges ----

double segment_distance(const V& p, const V& u, const V& v) {
  const V d = v - u;
  const double t = d.squaredNorm() > 0.0 ? std::clamp((p - u).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (p - (u + t * d)).norm();
}

double reference_distance(const V& p, const V& a, const V& b, const V& c) {
  double best = std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
  const V n = (b - a).cross(c - a);
  if (n.squaredNorm() > 1e-20 * std::pow((b - a).squaredNorm() + (c - a).squaredNorm(), 2)) {
    const V q = p - (p - a).dot(n) / n.squaredNorm() * n;
    // Inside when q is on the inner side of all three edges.
    const bool inside =
        (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 && (a - c).cross(q - c).dot(n) >= 0;
    if (inside) best = std::min(best, (p - q).norm());
  }
  return best;
}

const V& vertex(const Mesh& m, std::size_t f, int k) {
  return m.vertices[static_cast<std::size_t>(m.faces[f][static_cast<std::size_t>(k)])];
}

// The smallest (squared distance, face) over all faces within max_distance, by the same triangle routine.
SurfacePoint brute_force(const Mesh& m, const V& p, double max_distance) {
  SurfacePoint best;
  best.sq_distance = max_distance * max_distance;
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    SurfacePoint s = closest_point_on_triangle(p, vertex(m, f, 0), vertex(m, f, 1), vertex(m, f, 2));
    if (s.sq_distance < best.sq_distance || (s.sq_distance == best.sq_distance && best.face < 0)) {
      best = s;
      best.face = static_cast<int>(f);
    }
  }
  return best;
}

// ---- meshes ----

// Triangles with corners anywhere in a 100 mm cube: large, overlapping, intersecting; a few without area.
Mesh triangle_soup(int count, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 100.0);
  Mesh m;
  for (int i = 0; i < count; ++i) {
    const V a(u(rng), u(rng), u(rng));
    V b(u(rng), u(rng), u(rng));
    V c = a + (b - a) * 0.2 * static_cast<double>(i % 7) + V(u(rng), u(rng), u(rng)) * 0.1;
    if (i % 50 == 0) c = a + 2.5 * (b - a);  // collinear
    if (i % 50 == 1) b = a;                  // two corners in one place
    const auto base = static_cast<std::int32_t>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), {a, b, c});
    m.faces.push_back({base, base + 1, base + 2});
  }
  return m;
}

// A height field over an n x n grid with shared vertices (edges and vertices shared by several faces: ties).
Mesh height_field(int n, double step, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> h(-2.0, 2.0);
  Mesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) m.vertices.emplace_back(i * step, j * step, (i + j) % 3 == 0 ? 0.0 : h(rng));
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::int32_t v = j * (n + 1) + i;
      m.faces.push_back({v, v + 1, v + n + 2});
      m.faces.push_back({v, v + n + 2, v + n + 1});
    }
  }
  return m;
}

// The surface of the box [0, size]^3 with each side an n x n grid of squares, vertices shared, faces outward.
// Cells are split along the diagonal that passes through the side's centre (n even), so moving the centre vertex
// of a side makes a four-sided pyramid of it.
Mesh box_mesh(int n, double size) {
  Mesh m;
  std::map<std::int64_t, std::int32_t> ids;
  auto id = [&](const Eigen::Vector3i& g) {
    const std::int64_t key = (std::int64_t{g.x()} * (n + 1) + g.y()) * (n + 1) + g.z();
    auto [it, added] = ids.emplace(key, static_cast<std::int32_t>(m.vertices.size()));
    if (added) m.vertices.push_back(g.cast<double>() * size / n);
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      // u x v points out of the box: +axis for side 1, -axis for side 0.
      int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
      if (side == 0) std::swap(u_axis, v_axis);
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          auto corner = [&](int di, int dj) {
            Eigen::Vector3i g = Eigen::Vector3i::Zero();
            g[axis] = side * n;
            g[u_axis] = i + di;
            g[v_axis] = j + dj;
            return id(g);
          };
          const std::int32_t c00 = corner(0, 0), c10 = corner(1, 0), c11 = corner(1, 1), c01 = corner(0, 1);
          if ((i + j) % 2 == 0) {
            m.faces.push_back({c00, c10, c11});
            m.faces.push_back({c00, c11, c01});
          } else {
            m.faces.push_back({c00, c10, c01});
            m.faces.push_back({c10, c11, c01});
          }
        }
      }
    }
  }
  return m;
}

// A latitude-longitude sphere of radius r centred at the origin (convex; poles shared by a fan of faces).
Mesh uv_sphere(int rings, int segments, double r) {
  return test::lat_long_sphere(rings, segments, [r](double, double) { return r; });
}

double signed_distance(const TriangleIndex& index, const V& p) {
  const SurfacePoint s = index.closest(p);
  const double d = std::sqrt(s.sq_distance);
  return (p - s.point).dot(index.normal_at(s)) >= 0.0 ? d : -d;
}

// ---- closest_point_on_triangle ----

struct RegionCase {
  V query;
  V point;
  V barycentric;
  TriangleFeature feature;
};

TEST(ClosestPointOnTriangle, EveryVoronoiRegionMatchesTheAnalyticAnswer) {
  const V a(0, 0, 0), b(4, 0, 0), c(0, 3, 0);
  const std::vector<RegionCase> cases = {
      {{1, 1, 2}, {1, 1, 0}, {1 - 0.25 - 1.0 / 3, 0.25, 1.0 / 3}, TriangleFeature::kFace},
      {{1, 1, -2}, {1, 1, 0}, {1 - 0.25 - 1.0 / 3, 0.25, 1.0 / 3}, TriangleFeature::kFace},
      {{-1, -1, 1}, a, {1, 0, 0}, TriangleFeature::kVertex0},
      {{5, -1, 0}, b, {0, 1, 0}, TriangleFeature::kVertex1},
      {{-1, 4, 0.5}, c, {0, 0, 1}, TriangleFeature::kVertex2},
      {{2, -2, 1}, {2, 0, 0}, {0.5, 0.5, 0}, TriangleFeature::kEdge01},
      // The hypotenuse b-c: outward in-plane normal (3, 4, 0) / 5 from its middle (2, 1.5).
      {{5, 5.5, 2}, {2, 1.5, 0}, {0, 0.5, 0.5}, TriangleFeature::kEdge12},
      {{-2, 1.5, -1}, {0, 1.5, 0}, {0.5, 0, 0.5}, TriangleFeature::kEdge20},
      {{0, 0, 0}, a, {1, 0, 0}, TriangleFeature::kVertex0},  // on the surface itself
  };
  for (const RegionCase& r : cases) {
    const SurfacePoint s = closest_point_on_triangle(r.query, a, b, c);
    EXPECT_EQ(s.feature, r.feature) << r.query.transpose();
    EXPECT_NEAR((s.point - r.point).norm(), 0.0, 1e-12) << r.query.transpose();
    EXPECT_NEAR((s.barycentric - r.barycentric).norm(), 0.0, 1e-12) << r.query.transpose();
    EXPECT_NEAR(s.sq_distance, (r.query - r.point).squaredNorm(), 1e-12) << r.query.transpose();
    EXPECT_EQ(s.face, -1);
  }
}

TEST(ClosestPointOnTriangle, DegenerateTrianglesAreTheirSegmentOrPoint) {
  // Collinear corners: the triangle is the segment from a to c.
  const V a(0, 0, 0), b(1, 0, 0), c(3, 0, 0);
  SurfacePoint s = closest_point_on_triangle(V(2, 1, 0), a, b, c);
  EXPECT_NEAR((s.point - V(2, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.sq_distance, 1.0);
  EXPECT_NEAR(s.barycentric.sum(), 1.0, 1e-15);
  EXPECT_NEAR((s.barycentric[0] * a + s.barycentric[1] * b + s.barycentric[2] * c - s.point).norm(), 0.0, 1e-15);
  s = closest_point_on_triangle(V(-1, 0, 0), a, b, c);
  EXPECT_EQ(s.point, a);
  EXPECT_DOUBLE_EQ(s.sq_distance, 1.0);
  s = closest_point_on_triangle(V(5, 2, 0), a, b, c);
  EXPECT_EQ(s.point, c);
  EXPECT_DOUBLE_EQ(s.sq_distance, 8.0);

  // Two corners in one place: the segment between the distinct ones.
  s = closest_point_on_triangle(V(1, 1, 1), a, a, V(2, 0, 0));
  EXPECT_NEAR((s.point - V(1, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.sq_distance, 2.0);

  // All three in one place: a point.
  s = closest_point_on_triangle(V(1, 2, 2), b, b, b);
  EXPECT_EQ(s.point, b);
  EXPECT_DOUBLE_EQ(s.sq_distance, 8.0);
  EXPECT_TRUE(std::isfinite(s.barycentric.sum()));

  // Nearly collinear (area 1e-14 of the longest edge squared): no NaN, and the distance of the segment.
  s = closest_point_on_triangle(V(1.5, 2, 0), a, V(1, 1e-14, 0), c);
  EXPECT_NEAR(std::sqrt(s.sq_distance), 2.0, 1e-12);
}

// ---- the index against brute force ----

void expect_matches_brute_force(const Mesh& mesh, const std::vector<V>& queries, double max_distance) {
  const TriangleIndex index(mesh);
  ASSERT_EQ(index.face_count(), mesh.faces.size());
  for (const V& q : queries) {
    const SurfacePoint expected = brute_force(mesh, q, max_distance);
    const SurfacePoint got = index.closest(q, max_distance);
    ASSERT_EQ(got.face, expected.face) << "query " << q.transpose();
    if (!expected.found()) continue;
    ASSERT_EQ(got.sq_distance, expected.sq_distance) << "query " << q.transpose();
    ASSERT_EQ(got.point, expected.point);
    ASSERT_EQ(got.feature, expected.feature);
    // And against the independent projection-or-edges reference.
    double reference = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      reference =
          std::min(reference, reference_distance(q, vertex(mesh, f, 0), vertex(mesh, f, 1), vertex(mesh, f, 2)));
    }
    ASSERT_NEAR(std::sqrt(got.sq_distance), reference, 1e-9) << "query " << q.transpose();
  }
}

std::vector<V> random_queries(int count, double lo, double hi, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<V> queries;
  for (int i = 0; i < count; ++i) queries.emplace_back(u(rng), u(rng), u(rng));
  return queries;
}

TEST(TriangleIndex, EqualsBruteForceOnATriangleSoup) {
  std::mt19937_64 rng(20240611);
  const Mesh soup = triangle_soup(600, rng);
  std::vector<V> queries = random_queries(1500, -30.0, 130.0, rng);
  for (std::size_t i = 0; i < 60; ++i) queries.push_back(soup.vertices[i * 7]);  // on the surface
  expect_matches_brute_force(soup, queries, std::numeric_limits<double>::infinity());
  expect_matches_brute_force(soup, queries, 3.0);
}

TEST(TriangleIndex, EqualsBruteForceOnASharedVertexMeshWithTies) {
  std::mt19937_64 rng(7);
  const Mesh field = height_field(30, 2.0, rng);
  std::vector<V> queries = random_queries(1500, -5.0, 65.0, rng);
  for (V& q : queries) q.z() *= 0.1;
  // Exactly above grid vertices and edge midpoints: several faces at the same distance.
  for (int i = 0; i < 30; i += 3) queries.emplace_back(2.0 * i, 2.0 * i, 5.0);
  for (int i = 0; i < 30; i += 3) queries.emplace_back(2.0 * i + 1.0, 2.0 * i, 3.0);
  expect_matches_brute_force(field, queries, std::numeric_limits<double>::infinity());
  expect_matches_brute_force(field, queries, 1.0);
}

// closest_with_slots + closest_among (ICP's per-point cache): for a query moved anywhere within the reach, the same
// answer as closest(), on a mesh with shared vertices and ties and on a triangle soup; more than max_slots: none.
TEST(TriangleIndex, SlotsAnswerExactlyWithinTheirReach) {
  std::mt19937_64 rng(11);
  for (const Mesh& m : {height_field(20, 2.0, rng), triangle_soup(300, rng)}) {
    const TriangleIndex index(m);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int reused = 0;
    std::vector<V> anchors = random_queries(300, 0.0, 40.0, rng);
    for (V& a : anchors) a.z() *= m.faces.size() == 800 ? 0.05 : 1.0;  // near the height field's surface
    for (const V& anchor : anchors) {
      for (double max_distance : {std::numeric_limits<double>::infinity(), 1.5}) {
        std::vector<std::int32_t> slots;
        double reach = 0.0;
        const SurfacePoint at = index.closest_with_slots(anchor, max_distance, 0.3, 16, slots, &reach);
        const SurfacePoint expected = index.closest(anchor, max_distance);
        EXPECT_EQ(at.face, expected.face);
        EXPECT_EQ(at.sq_distance, expected.sq_distance);
        if (!at.found()) {
          EXPECT_TRUE(slots.empty());
          continue;
        }
        EXPECT_EQ(reach, std::max(0.3, std::sqrt(at.sq_distance)));
        if (slots.empty()) continue;  // more than 16 triangles within reach
        ++reused;
        for (int k = 0; k < 20; ++k) {
          V step(u(rng), u(rng), u(rng));
          step *= reach * (k == 0 ? 1.0 : std::abs(u(rng))) / step.norm();  // up to the reach itself
          const V q = anchor + step;
          const SurfacePoint a = index.closest_among(q, slots.data(), slots.size(), max_distance);
          const SurfacePoint b = index.closest(q, max_distance);
          ASSERT_EQ(a.face, b.face) << q.transpose();
          EXPECT_EQ(a.sq_distance, b.sq_distance);
          EXPECT_EQ(a.point, b.point);
        }
      }
    }
    EXPECT_GT(reused, 10);  // the check above ran
  }
  // A fan of 20 triangles around one vertex: a query at it has all 20 within any reach, more than 8 slots.
  Mesh fan;
  fan.vertices.emplace_back(0, 0, 0);
  for (int k = 0; k < 20; ++k) fan.vertices.emplace_back(std::cos(k * M_PI / 10), std::sin(k * M_PI / 10), 0.0);
  for (std::int32_t k = 0; k < 20; ++k) fan.faces.push_back({0, 1 + k, 1 + (k + 1) % 20});
  std::vector<std::int32_t> slots;
  double reach = 0.0;
  EXPECT_TRUE(TriangleIndex(fan).closest_with_slots(V(0, 0, 0.1), 5.0, 0.01, 8, slots, &reach).found());
  EXPECT_TRUE(slots.empty());
}

TEST(TriangleIndex, TiesGoToTheLowerFaceIndex) {
  // The same triangle twice, and a query above its middle: both faces are equally close.
  Mesh m;
  m.vertices = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  m.faces = {{0, 1, 2}, {0, 1, 2}, {0, 1, 2}};
  const TriangleIndex index(m);
  EXPECT_EQ(index.closest(V(0.2, 0.2, 1)).face, 0);
}

TEST(TriangleIndex, MaxDistanceIsAnInclusiveCutOff) {
  Mesh m;
  m.vertices = {V(0, 0, 0), V(10, 0, 0), V(0, 10, 0)};
  m.faces = {{0, 1, 2}};
  const TriangleIndex index(m);
  const V q(2, 2, 2);
  EXPECT_TRUE(index.closest(q, 2.0).found());
  EXPECT_DOUBLE_EQ(index.closest(q, 2.0).sq_distance, 4.0);
  const SurfacePoint none = index.closest(q, 1.999);
  EXPECT_FALSE(none.found());
  EXPECT_TRUE(index.closest(V(1, 1, 0), 0.0).found());
  EXPECT_EQ(index.normal_at(none), V::Zero());
  EXPECT_THROW(index.closest(q, -1.0), Error);
  EXPECT_THROW(index.closest(q, std::numeric_limits<double>::quiet_NaN()), Error);
  EXPECT_THROW(index.closest(V(0, std::numeric_limits<double>::infinity(), 0)), Error);
}

TEST(TriangleIndex, RejectsMeshesItCannotIndex) {
  Mesh cloud;
  cloud.vertices = {V(0, 0, 0)};
  EXPECT_THROW(TriangleIndex{cloud}, Error);
  Mesh bad_index;
  bad_index.vertices = {V(0, 0, 0), V(1, 0, 0)};
  bad_index.faces = {{0, 1, 2}};
  EXPECT_THROW(TriangleIndex{bad_index}, Error);
  Mesh nan_vertex = bad_index;
  nan_vertex.vertices.emplace_back(0, std::nan(""), 0);
  EXPECT_THROW(TriangleIndex{nan_vertex}, Error);
}

// ---- pseudo-normals and the sign of the distance ----

TEST(TriangleIndex, PseudoNormalsOfABoxAreExactWhateverTheTriangulation) {
  const TriangleIndex index(box_mesh(4, 10.0));
  // At a corner each side adds a right angle: (1, 1, 1) / sqrt(3) however the sides are cut into triangles.
  SurfacePoint s = index.closest(V(10.5, 10.2, 10.1));
  EXPECT_EQ(s.point, V(10, 10, 10));
  EXPECT_NEAR((index.normal_at(s) - V(1, 1, 1).normalized()).norm(), 0.0, 1e-12);
  // Along an edge, the mean of the two sides.
  s = index.closest(V(10.0, 10.2, 3.3));
  EXPECT_NEAR((index.normal_at(s) - V(1, 1, 0).normalized()).norm(), 0.0, 1e-12) << index.normal_at(s);
  EXPECT_GT((V(10.0, 10.2, 3.3) - s.point).dot(index.normal_at(s)), 0.0);
  // Inside a side: the side's normal.
  s = index.closest(V(3.3, 4.4, -1));
  EXPECT_EQ(s.feature, TriangleFeature::kFace);
  EXPECT_NEAR((index.normal_at(s) - V(0, 0, -1)).norm(), 0.0, 1e-15);
}

// Signs at points all around a closed mesh against the truth `inside`; points within 1e-9 mm are not judged.
template <typename Inside>
void expect_signs(const Mesh& mesh, const std::vector<V>& points, Inside inside) {
  const TriangleIndex index(mesh);
  int judged = 0;
  for (const V& p : points) {
    const double d = signed_distance(index, p);
    if (std::abs(d) < 1e-9) continue;
    ++judged;
    ASSERT_EQ(d < 0.0, inside(p)) << "point " << p.transpose() << ", signed distance " << d;
  }
  EXPECT_GT(judged, static_cast<int>(points.size()) * 9 / 10);
}

// Random points near the given features (vertices and edge points), within `spread` of them.
std::vector<V> points_near(const std::vector<V>& features, double spread, int per_feature, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<V> points;
  for (const V& f : features) {
    for (int i = 0; i < per_feature; ++i) points.push_back(f + V(u(rng), u(rng), u(rng)));
  }
  return points;
}

TEST(TriangleIndex, SignIsRightNearTheEdgesAndCornersOfABox) {
  std::mt19937_64 rng(3);
  const Mesh box = box_mesh(2, 10.0);
  std::vector<V> features = box.vertices;
  for (const Face& f : box.faces) features.push_back(0.5 * (box.vertices[f[0]] + box.vertices[f[1]]));
  std::vector<V> points = points_near(features, 0.3, 20, rng);
  // Exactly in the plane of a side, just beyond an edge: the side's own normal would say 0.
  points.emplace_back(10.0, 10.2, 5.0);
  points.emplace_back(-0.2, 0.0, 5.0);
  expect_signs(box, points, [](const V& p) { return (p.array() > 0.0).all() && (p.array() < 10.0).all(); });
}

TEST(TriangleIndex, SignIsRightAroundADentedBox) {
  // The top's centre pushed down 3 mm: a concave vertex, valley edges and saddle-like corners.
  Mesh dented = box_mesh(2, 10.0);
  for (V& v : dented.vertices) {
    if (v == V(5, 5, 10)) v.z() = 7.0;
  }
  std::mt19937_64 rng(5);
  std::vector<V> features = dented.vertices;
  for (const Face& f : dented.faces) features.push_back(0.5 * (dented.vertices[f[1]] + dented.vertices[f[2]]));
  const std::vector<V> points = points_near(features, 0.4, 30, rng);
  expect_signs(dented, points, [](const V& p) {
    const double top = 7.0 + 0.6 * std::max(std::abs(p.x() - 5.0), std::abs(p.y() - 5.0));
    return p.x() > 0 && p.x() < 10 && p.y() > 0 && p.y() < 10 && p.z() > 0 && p.z() < top;
  });
}

TEST(TriangleIndex, SignIsRightAroundASphereLikeMesh) {
  const Mesh sphere = uv_sphere(12, 16, 10.0);
  std::vector<V> face_normals;
  for (std::size_t f = 0; f < sphere.faces.size(); ++f) face_normals.push_back(face_normal(sphere, f));
  std::mt19937_64 rng(11);
  std::vector<V> features = sphere.vertices;
  for (const Face& f : sphere.faces) features.push_back(0.5 * (sphere.vertices[f[0]] + sphere.vertices[f[1]]));
  const std::vector<V> points = points_near(features, 0.3, 8, rng);
  // Convex: inside exactly when behind every face's plane.
  expect_signs(sphere, points, [&](const V& p) {
    for (std::size_t f = 0; f < sphere.faces.size(); ++f) {
      if ((p - vertex(sphere, f, 0)).dot(face_normals[f]) >= 0.0) return false;
    }
    return true;
  });
}

TEST(TriangleIndex, AFaceWithoutAreaTakesItsNeighboursSide) {
  // A flat square of four triangles around its centre, and first a zero-area sliver along the diagonal 0-4-2.
  Mesh m;
  m.vertices = {V(0, 0, 0), V(10, 0, 0), V(10, 10, 0), V(0, 10, 0), V(5, 5, 0)};
  m.faces = {{0, 4, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  const TriangleIndex index(m);
  for (double z : {1.0, -1.0}) {
    const SurfacePoint centre = index.closest(V(5, 5, z));
    EXPECT_EQ(centre.face, 0);  // every face is 1 mm away; the sliver has the lowest index
    EXPECT_EQ(centre.feature, TriangleFeature::kVertex1);
    EXPECT_DOUBLE_EQ(centre.sq_distance, 1.0);
    EXPECT_NEAR((index.normal_at(centre) - V(0, 0, 1)).norm(), 0.0, 1e-15);
    for (const V& q : {V(5, 5, z), V(2.5, 2.5, z), V(7.5, 7.5, z)}) {
      EXPECT_EQ(signed_distance(index, q) > 0.0, z > 0.0) << q.transpose();
    }
  }
}

}  // namespace
}  // namespace conform
