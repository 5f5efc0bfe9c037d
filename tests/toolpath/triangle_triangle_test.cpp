// Exact orientation and the perturbed triangle-triangle intersection, on the degenerate configurations rounding
// gets wrong: points exactly coplanar far from the origin, vertices on the other triangle's plane, shared edges.

#include "conform/toolpath/intersection/triangle_triangle.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "conform/toolpath/intersection/exact_orientation.h"

namespace conform {
namespace {

TEST(ExactOrientation, SignsOfAPlainTetrahedron) {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_EQ(orient3d_sign(a, b, c, {0.2, 0.2, 1.0}), 1);
  EXPECT_EQ(orient3d_sign(a, b, c, {0.2, 0.2, -1.0}), -1);
  EXPECT_EQ(orient3d_sign(a, b, c, {0.2, 0.7, 0.0}), 0);
  EXPECT_EQ(orient3d_sign(b, a, c, {0.2, 0.2, 1.0}), -1);  // swapping two vertices flips it
}

// Coplanar points far from the origin: z = (x + y) / 4 on dyadic coordinates is exact in double, so the true
// determinant is 0; the rounded one is not, and a point one ulp off the plane has a sign the filter cannot see.
TEST(ExactOrientation, CoplanarPointsFarFromTheOriginAreExactlyZeroAndOneUlpOffIsSeen) {
  std::mt19937 rng(3);
  // 32-bit coordinates (2^-20 mm steps, 4 m from the origin): the differences are exact, their triple products
  // need ~96 bits, so the rounded determinant is noise.
  std::uniform_int_distribution<long long> coordinate(-(1LL << 31), 1LL << 31);
  const double offset = 4096.0;
  const double step = std::ldexp(1.0, -20);
  int rounded_wrong = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Vector3d p[4];
    for (Eigen::Vector3d& q : p) {
      const double x = offset + static_cast<double>(coordinate(rng)) * step;
      const double y = offset + static_cast<double>(coordinate(rng)) * step;
      q = {x, y, (x + y) / 4.0};
    }
    EXPECT_EQ(orient3d_sign(p[0], p[1], p[2], p[3]), 0) << trial;
    if (orient3d(p[0], p[1], p[2], p[3]) != 0.0) ++rounded_wrong;
    const double normal_z = ((p[1] - p[0]).cross(p[2] - p[0])).z();
    if (normal_z == 0.0) continue;
    Eigen::Vector3d above = p[3];
    above.z() = std::nextafter(above.z(), 1e300);
    EXPECT_EQ(orient3d_sign(p[0], p[1], p[2], above), normal_z > 0 ? 1 : -1) << trial;
  }
  std::printf("rounded orient3d nonzero on %d of 2000 exactly coplanar quadruples\n", rounded_wrong);
}

IndexedTriangle triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int first,
                         int face) {
  IndexedTriangle t;
  t.p[0] = a;
  t.p[1] = b;
  t.p[2] = c;
  t.index[0] = first;
  t.index[1] = first + 1;
  t.index[2] = first + 2;
  t.face = face;
  return t;
}

TEST(TriangleTriangle, CrossingTrianglesGiveOneSegmentOnBoth) {
  const IndexedTriangle a = triangle({-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}, 0, 0);
  const IndexedTriangle b = triangle({0.2, 0.3, -1}, {0.2, 0.3, 1}, {0.2, -2, 0}, 10, 5);
  EdgeCrossing ends[6];
  ASSERT_EQ(intersect_triangles(a, b, ends), 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(ends[i].point.z(), 0.0, 1e-15);  // on a's plane
    EXPECT_NEAR(ends[i].point.x(), 0.2, 1e-15);  // on b's plane
  }
}

TEST(TriangleTriangle, DisjointAndParallelTrianglesDoNotIntersect) {
  const IndexedTriangle a = triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0, 0);
  EdgeCrossing ends[6];
  EXPECT_EQ(intersect_triangles(a, triangle({0, 0, 1}, {1, 0, 1}, {0, 1, 1}, 3, 1), ends), 0);
  EXPECT_EQ(intersect_triangles(a, triangle({5, 5, -1}, {5, 5, 1}, {6, 5, 0}, 3, 1), ends), 0);
}

// Coplanar triangles overlap in an area, not along a curve: under the perturbation B is lifted off A's plane, so
// there is no crossing at all — never a half-answer.
TEST(TriangleTriangle, CoplanarOverlappingTrianglesGiveNoCrossing) {
  const IndexedTriangle a = triangle({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0, 0);
  const IndexedTriangle b = triangle({0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0}, 3, 1);
  EdgeCrossing ends[6];
  EXPECT_EQ(intersect_triangles(a, b, ends), 0);
}

// A vertex of B exactly on A's plane and inside A, the two other vertices on either side: the perturbation decides
// which side the vertex is on; whichever it is, the count is 0 or 2, never 1 or 3.
TEST(TriangleTriangle, VertexOnThePlaneGivesAnEvenCountForEveryOrientation) {
  const IndexedTriangle a = triangle({-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}, 0, 0);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Vector3d on(0.25 * std::round(4 * u(rng)), 0.25 * std::round(4 * u(rng)), 0.0);
    const IndexedTriangle b = triangle(on, {u(rng), u(rng), 1.0 + u(rng)}, {u(rng), u(rng), -1.0 - u(rng)}, 3, 1);
    EdgeCrossing ends[6];
    const int count = intersect_triangles(a, b, ends);
    EXPECT_TRUE(count == 0 || count == 2) << trial << ": " << count;
  }
}

}  // namespace
}  // namespace conform
