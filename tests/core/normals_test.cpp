#include "conform/core/normals.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {
namespace {

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// Largest and mean of a set of errors.
struct Stats {
  double max = 0.0, sum = 0.0;
  std::size_t count = 0;
  void add(double value) {
    max = std::max(max, value);
    sum += value;
    ++count;
  }
  double mean() const { return count > 0 ? sum / static_cast<double>(count) : 0.0; }
};

Eigen::Vector3d normal_at(const pcl::PointCloud<pcl::Normal>& normals, std::size_t i) {
  return normals[i].getNormalVector3fMap().cast<double>();
}

Cloud cloud_of(const std::vector<Eigen::Vector3d>& points) {
  Cloud cloud;
  for (const Eigen::Vector3d& p : points) {
    cloud.points.push_back(
        pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  }
  return cloud;
}

// Points of the plane x + 2y + 2z = 5e4 (unit normal (1, 2, 2) / 3), about 1e4 mm from the origin in every coordinate.
// They are o + s a + t b with dyadic s, t and in-plane a = (2, -1, 0), b = (0, 1, -1), so every coordinate is exact in
// float: the plane the estimator sees is exactly the analytic one. `width` limits t, to make thin strips.
Cloud plane_cloud(int n, double length, double width, std::mt19937& rng) {
  const Eigen::Vector3d o(1e4, 1e4, 1e4), a(2, -1, 0), b(0, 1, -1);
  std::uniform_int_distribution<int> s(0, static_cast<int>(length * 64)), t(0, static_cast<int>(width * 1024));
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) points.push_back(o + (s(rng) / 64.0) * a + (t(rng) / 1024.0) * b);
  return cloud_of(points);
}

const Eigen::Vector3d kPlaneNormal = Eigen::Vector3d(1, 2, 2) / 3.0;

TEST(EstimateNormals, PlaneFarFromOriginIsExact) {
  std::mt19937 rng(1);
  const Cloud cloud = plane_cloud(4000, 20.0, 40.0, rng);
  NormalOptions options;
  options.viewpoint = Eigen::Vector3d(1e4, 1e4, 1e4) + 500.0 * kPlaneNormal;
  const auto normals = estimate_normals(cloud, options);
  ASSERT_EQ(normals.size(), cloud.size());
  double worst = 0.0, worst_curvature = 0.0;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    worst = std::max(worst, (normal_at(normals, i) - kPlaneNormal).norm());
    worst_curvature = std::max(worst_curvature, static_cast<double>(normals[i].curvature));
  }
  // The double PCA is exact to ~1e-15 (next test); what remains is the rounding of the float output, half an ulp per
  // component: sqrt((2^-26)^2 + 2 (2^-25)^2) = 4.5e-8 for (1, 2, 2) / 3 (measured 3.0e-8).
  EXPECT_LT(worst, 4.5e-8);
  EXPECT_LT(worst_curvature, 1e-12);  // measured 2.6e-16
}

// The PCA itself, without the float output: the Mesh overload returns double normals.
Mesh plane_mesh(const Cloud& cloud) {
  Mesh mesh = to_mesh(cloud);
  mesh.faces.push_back({0, 1, 2});  // only to orient by: a face whose normal is +/- the plane normal
  const Eigen::Vector3d n = (mesh.vertices[1] - mesh.vertices[0]).cross(mesh.vertices[2] - mesh.vertices[0]);
  if (n.dot(kPlaneNormal) < 0.0) std::swap(mesh.faces[0][1], mesh.faces[0][2]);
  return mesh;
}

TEST(EstimateNormals, PlaneNormalIsExactInDoubleEvenForThinStrips) {
  std::mt19937 rng(2);
  // A round neighbourhood and a strip about 1/1000 as wide as its neighbourhoods are long: the strip is where Eigen's
  // closed-form computeDirect() loses the smallest eigenvector (4.7e-5 here instead of 2.9e-11).
  for (double width : {20.0, 0.002}) {
    Cloud cloud = plane_cloud(width > 1.0 ? 3000 : 300, 20.0, width, rng);
    // Three distinct, non-collinear vertices first, for the orienting face.
    const Cloud corner = cloud_of({Eigen::Vector3d(1e4, 1e4, 1e4), Eigen::Vector3d(1e4 + 2, 1e4 - 1, 1e4),
                                   Eigen::Vector3d(1e4, 1e4 + 1.0 / 64, 1e4 - 1.0 / 64)});
    cloud.points.insert(cloud.points.begin(), corner.points.begin(), corner.points.end());
    const std::vector<Eigen::Vector3d> normals = estimate_normals(plane_mesh(cloud), 16);
    // Only the first three vertices have a face, and the rest are oriented by whether their neighbours include them:
    // compare up to sign (orientation is tested below).
    Stats error;
    for (const Eigen::Vector3d& n : normals) error.add(std::min((n - kPlaneNormal).norm(), (n + kPlaneNormal).norm()));
    EXPECT_LT(error.max, 1e-9) << "width " << width << " mm";  // measured 8.5e-16 (round), 2.9e-11 (strip)
  }
}

std::vector<Eigen::Vector3d> random_unit_vectors(int n, std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) out.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  return out;
}

// Sphere of radius 50 mm, 20000 random points (mean spacing about 1.25 mm), k = 16.
TEST(EstimateNormals, SphereNormalsAreRadialAndPointToTheViewpoint) {
  std::mt19937 rng(3);
  const Eigen::Vector3d centre(100.0, -200.0, 300.0);
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& u : random_unit_vectors(20000, rng)) points.push_back(centre + 50.0 * u);
  const Cloud cloud = cloud_of(points);
  NormalOptions options;
  options.viewpoint = centre;  // inside: every normal points inwards
  const auto normals = estimate_normals(cloud, options);
  Stats error;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].getVector3fMap().cast<double>();
    error.add(angle(normal_at(normals, i), centre - p));
    ASSERT_NEAR(normal_at(normals, i).norm(), 1.0, 1e-6);
  }
  // The PCA normal is the surface normal near the neighbourhood's centroid, which can lie up to about half the
  // neighbourhood radius rho (~2.8 mm here) from the point: error up to rho / (2 R) = 0.028 (measured max 0.030,
  // mean 0.0066).
  EXPECT_LT(error.max, 0.05);  // rad
  EXPECT_LT(error.mean(), 0.01);

  options.viewpoint = centre + Eigen::Vector3d(0.0, 0.0, 1000.0);  // far above: the upper half faces it
  const auto up = estimate_normals(cloud, options);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d p = cloud.points[i].getVector3fMap().cast<double>();
    EXPECT_GE(normal_at(up, i).dot(options.viewpoint - p), 0.0) << "point " << i;
  }
}

// Normals over a tree already built (IcpReference's way, from double points): the plane's analytic normal exactly
// (as PlaneFarFromOriginIsExact), and bit for bit those of the same points given as a cloud.
TEST(EstimateNormals, OverABuiltTreeAreTheCloudsOwn) {
  std::mt19937 rng(21);
  const Cloud cloud = plane_cloud(3000, 40.0, 30.0, rng);
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : cloud.points) points.push_back(p.getVector3fMap().cast<double>());
  NormalOptions options;
  options.viewpoint = Eigen::Vector3d(1e5, 1e5, 1e5);
  const KdTree tree(points);
  const auto from_tree = estimate_normals(tree, options);
  const auto from_cloud = estimate_normals(cloud, options);
  ASSERT_EQ(from_tree.size(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    EXPECT_LT(angle(normal_at(from_tree, i), kPlaneNormal), 1e-6) << i;
    ASSERT_EQ(std::memcmp(&from_tree[i], &from_cloud[i], sizeof(pcl::Normal)), 0) << i;
  }
  EXPECT_THROW(estimate_normals(KdTree(std::vector<Eigen::Vector3d>(2, Eigen::Vector3d::Zero())), options), Error);
}

// Cylinder of radius 30 mm, length 120 mm around an axis through (10, -5, 0) along z, 20000 random points (mean
// spacing about 1.07 mm), k = 16.
TEST(EstimateNormals, CylinderNormalsPointAwayFromOrTowardsTheAxis) {
  std::mt19937 rng(4);
  const Eigen::Vector3d axis_point(10.0, -5.0, 0.0);
  std::uniform_real_distribution<double> phi(0.0, 2.0 * kPi), z(-60.0, 60.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 20000; ++i) {
    const double a = phi(rng);
    points.push_back(axis_point + Eigen::Vector3d(30.0 * std::cos(a), 30.0 * std::sin(a), z(rng)));
  }
  const Cloud cloud = cloud_of(points);
  NormalOptions options;
  options.orientation = NormalOrientation::kAwayFromAxis;
  options.axis_point = axis_point + Eigen::Vector3d(0.0, 0.0, 17.0);  // any point of the axis
  options.axis_direction = Eigen::Vector3d(0.0, 0.0, -5.0);           // any length, either sense
  const auto away = estimate_normals(cloud, options);
  options.orientation = NormalOrientation::kTowardsAxis;
  const auto towards = estimate_normals(cloud, options);
  Stats error;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    Eigen::Vector3d radial = cloud.points[i].getVector3fMap().cast<double>() - axis_point;
    radial.z() = 0.0;
    error.add(angle(normal_at(away, i), radial));
    ASSERT_EQ(normal_at(towards, i), -normal_at(away, i)) << "point " << i;
    EXPECT_EQ(towards[i].curvature, away[i].curvature);
  }
  // rho ~2.4 mm against R = 30 mm, one-sided neighbourhoods at the ends (measured max 0.039, mean 0.0085).
  EXPECT_LT(error.max, 0.06);  // rad
  EXPECT_LT(error.mean(), 0.012);
  // The flattest neighbourhood on this noise-free curved surface: a few points take a neighbour's plane, up to
  // rho / R off (measured max 0.062, mean 0.0086).
  options.flattest_neighbourhood = true;
  const auto flattest = estimate_normals(cloud, options);
  Stats flattest_error;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    Eigen::Vector3d radial = cloud.points[i].getVector3fMap().cast<double>() - axis_point;
    radial.z() = 0.0;
    flattest_error.add(angle(normal_at(flattest, i), -radial));
  }
  EXPECT_LT(flattest_error.max, 0.08);
  EXPECT_LT(flattest_error.mean(), 0.012);
}

// A torus around the z axis (centre-line radius 60 mm, tube radius 20 mm) as a grid of nu x nv vertices; faces wind
// counter-clockwise seen from outside, unless `reversed`. Its normals point every way, inwards to the z axis on the
// inner side: only the faces can orient them.
constexpr double kTorusMajor = 60.0, kTorusMinor = 20.0;

Eigen::Vector3d torus_point(double u, double v) {
  return Eigen::Vector3d((kTorusMajor + kTorusMinor * std::cos(v)) * std::cos(u),
                         (kTorusMajor + kTorusMinor * std::cos(v)) * std::sin(u), kTorusMinor * std::sin(v));
}

// Outward normal at a point of the torus: away from the nearest point of the centre-line circle.
Eigen::Vector3d torus_normal(const Eigen::Vector3d& p) {
  const Eigen::Vector3d centre_line = kTorusMajor * Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
  return (p - centre_line).normalized();
}

Mesh torus(int nu, int nv, bool reversed) {
  Mesh mesh;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) mesh.vertices.push_back(torus_point(2.0 * kPi * i / nu, 2.0 * kPi * j / nv));
  }
  const auto at = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      // d/du x d/dv points outwards, so (i, j) -> (i + 1, j) -> (i + 1, j + 1) is counter-clockwise from outside.
      mesh.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.faces.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  if (reversed) {
    for (Face& f : mesh.faces) std::swap(f[1], f[2]);
  }
  return mesh;
}

// 150 x 50 vertices: spacing 2.5 mm across the tube, 1.7 to 3.4 mm around the z axis; k = 16.
TEST(EstimateNormals, MeshNormalsFollowTheFaceWinding) {
  const Mesh outward = torus(150, 50, false);
  for (std::size_t f = 0; f < outward.faces.size(); ++f) {  // the generator winds as documented
    const Eigen::Vector3d& a = outward.vertices[static_cast<std::size_t>(outward.faces[f][0])];
    ASSERT_GT(face_normal(outward, f).dot(torus_normal(a)), 0.0) << "face " << f;
  }
  const std::vector<Eigen::Vector3d> out = estimate_normals(outward, 16);
  const std::vector<Eigen::Vector3d> in = estimate_normals(torus(150, 50, true), 16);
  const std::vector<Eigen::Vector3d> faces = vertex_normals_from_faces(outward);
  ASSERT_EQ(out.size(), outward.vertices.size());
  Stats error;
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_GT(out[i].dot(faces[i]), 0.0) << "vertex " << i;
    EXPECT_EQ(in[i], -out[i]) << "vertex " << i;
    error.add(angle(out[i], torus_normal(outward.vertices[i])));
  }
  // k = 16 spans about +-2 grid steps (+-0.25 rad) across the tube; the bias of uneven neighbourhoods is a fraction of
  // that (measured max 0.032, mean 0.017).
  EXPECT_LT(error.max, 0.05);  // rad
  EXPECT_LT(error.mean(), 0.025);
}

TEST(EstimateNormals, VertexWithoutFacesBorrowsItsNeighboursOrientation) {
  Mesh mesh = torus(150, 50, true);                  // inward
  const Eigen::Vector3d p = torus_point(0.01, 2.0);  // between grid vertices, on the inner side of the tube
  mesh.vertices.push_back(p);
  const std::vector<Eigen::Vector3d> normals = estimate_normals(mesh, 16);
  EXPECT_LT(angle(normals.back(), -torus_normal(p)), 0.08);  // rad; measured 0.042 (a lopsided neighbourhood)
}

TEST(EstimateNormals, SameResultWithOneAndTwoThreads) {
  std::mt19937 rng(5);
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& u : random_unit_vectors(30000, rng)) points.push_back(25.0 * u);
  const Cloud cloud = cloud_of(points);
  const NormalOptions options;
  omp_set_num_threads(1);
  const auto one = estimate_normals(cloud, options);
  omp_set_num_threads(2);
  ASSERT_EQ(omp_get_max_threads(), 2);
  const auto two = estimate_normals(cloud, options);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(pcl::Normal)), 0);
  const Mesh mesh = torus(100, 40, false);
  omp_set_num_threads(1);
  const auto mesh_one = estimate_normals(mesh, 16);
  omp_set_num_threads(2);
  EXPECT_EQ(mesh_one, estimate_normals(mesh, 16));
}

void expect_finite_unit(const pcl::Normal& n) {
  const Eigen::Vector3d v = n.getNormalVector3fMap().cast<double>();
  ASSERT_TRUE(v.allFinite());
  EXPECT_NEAR(v.norm(), 1.0, 1e-6);
  EXPECT_EQ(n.curvature, 0.0f);
}

TEST(EstimateNormals, DegenerateNeighbourhoodsGiveDefinedNormals) {
  NormalOptions options;
  options.viewpoint = Eigen::Vector3d(5.0, 3.0, 4.0);
  // All points coincide: the unit direction to the viewpoint.
  const auto same =
      estimate_normals(cloud_of(std::vector<Eigen::Vector3d>(10, Eigen::Vector3d(5.0, 0.0, 0.0))), options);
  for (const pcl::Normal& n : same) {
    expect_finite_unit(n);
    EXPECT_LT((n.getNormalVector3fMap().cast<double>() - Eigen::Vector3d(0.0, 0.6, 0.8)).norm(), 1e-7);
  }
  // Collinear along x: the part of the viewpoint direction perpendicular to the line, (0, 3, 4) / 5.
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i < 20; ++i) line.push_back(Eigen::Vector3d(0.5 * i, 0.0, 0.0));
  for (const pcl::Normal& n : estimate_normals(cloud_of(line), options)) {
    expect_finite_unit(n);
    EXPECT_LT((n.getNormalVector3fMap().cast<double>() - Eigen::Vector3d(0.0, 0.6, 0.8)).norm(), 1e-7);
  }
  // Collinear along a slanted line: again the viewpoint direction's part perpendicular to the line, point by point.
  line.clear();
  for (int i = 0; i < 20; ++i) line.push_back(Eigen::Vector3d(1.0, 2.0, -1.0) * i);
  const Eigen::Vector3d d = Eigen::Vector3d(1.0, 2.0, -1.0).normalized();
  const auto slanted = estimate_normals(cloud_of(line), options);
  for (std::size_t i = 0; i < line.size(); ++i) {
    expect_finite_unit(slanted[i]);
    const Eigen::Vector3d r = options.viewpoint - line[i];
    EXPECT_LT((normal_at(slanted, i) - (r - r.dot(d) * d).normalized()).norm(), 1e-6) << "point " << i;
  }
  // Coincident points sitting on the viewpoint: no direction to prefer, still a finite unit normal.
  options.viewpoint = Eigen::Vector3d(5.0, 0.0, 0.0);
  for (const pcl::Normal& n :
       estimate_normals(cloud_of(std::vector<Eigen::Vector3d>(4, Eigen::Vector3d(5.0, 0.0, 0.0))), options)) {
    expect_finite_unit(n);
  }
}

// A 90-degree crease z = |y| (faces' normals (0, -1, 1) / sqrt 2 and (0, 1, 1) / sqrt 2), 20000 random points over
// 50 x 50 mm (spacing ~0.5 mm, a 16-neighbourhood reaches ~1.1 mm) with 0.02 mm noise along z. Plain PCA tilts the
// normal of every point within a neighbourhood radius of the crease towards the other face; the flattest
// neighbourhood gives such a point its own face's normal unless it lies on the other face's plane within the noise.
TEST(EstimateNormals, NearACreaseEachPointTakesItsOwnFacesNormal) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-25.0, 25.0);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 20000; ++i) {
    const double x = u(rng), y = u(rng);
    points.emplace_back(x, y, std::abs(y) + noise(rng));
  }
  const Cloud cloud = cloud_of(points);
  NormalOptions options;
  options.viewpoint = Eigen::Vector3d(0.0, 0.0, 1000.0);
  const auto plain = estimate_normals(cloud, options);  // the default
  options.flattest_neighbourhood = true;
  const auto flattest = estimate_normals(cloud, options);
  Stats near_flattest, near_plain, far_flattest;  // near: 0.2-1.5 mm from the crease (along y); far: beyond 3 mm
  int off_flattest = 0, off_plain = 0;            // near points more than 0.1 rad off
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double y = points[i].y();
    const Eigen::Vector3d truth = Eigen::Vector3d(0.0, y < 0.0 ? 1.0 : -1.0, 1.0).normalized();
    if (std::abs(y) > 3.0) far_flattest.add(angle(normal_at(flattest, i), truth));
    if (std::abs(y) < 0.2 || std::abs(y) > 1.5) continue;
    near_flattest.add(angle(normal_at(flattest, i), truth));
    near_plain.add(angle(normal_at(plain, i), truth));
    off_flattest += angle(normal_at(flattest, i), truth) > 0.1 ? 1 : 0;
    off_plain += angle(normal_at(plain, i), truth) > 0.1 ? 1 : 0;
  }
  std::printf(
      "  crease: near %.4f / %.4f rad (mean / max), %d of %zu off by > 0.1 rad; plain PCA %.4f / %.4f, %d; far "
      "%.4f / %.4f\n",
      near_flattest.mean(), near_flattest.max, off_flattest, near_flattest.count, near_plain.mean(), near_plain.max,
      off_plain, far_flattest.mean(), far_flattest.max);
  EXPECT_GT(near_plain.max, 0.3);  // plain PCA: up to ~half the crease's angle
  EXPECT_LT(near_flattest.mean(), 0.3 * near_plain.mean());
  EXPECT_LT(off_flattest, off_plain / 5);
  EXPECT_LT(far_flattest.max, 0.1);
  // The same with one and two threads, and over a tree already built.
  omp_set_num_threads(1);
  const auto one = estimate_normals(cloud, options);
  omp_set_num_threads(2);
  EXPECT_EQ(std::memcmp(one.data(), flattest.data(), one.size() * sizeof(pcl::Normal)), 0);
  const auto over_tree = estimate_normals(KdTree(cloud.points), options);
  EXPECT_EQ(std::memcmp(over_tree.data(), flattest.data(), one.size() * sizeof(pcl::Normal)), 0);
}

TEST(EstimateNormals, KLargerThanTheCloudUsesAllPoints) {
  const Cloud cloud = cloud_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0.5, 0.25, 0}});
  NormalOptions options;
  options.viewpoint = Eigen::Vector3d(0.0, 0.0, -10.0);
  for (const pcl::Normal& n : estimate_normals(cloud, options)) {
    EXPECT_EQ(n.getNormalVector3fMap(), Eigen::Vector3f(0.0f, 0.0f, -1.0f));
  }
}

TEST(NormalOptions, IsValidExplainsWhatIsWrong) {
  std::string error;
  EXPECT_TRUE(NormalOptions().IsValid(&error));
  EXPECT_TRUE(NormalOptions().IsValid(nullptr));
  NormalOptions options;
  options.k = 2;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("k = 2"), std::string::npos) << error;
  options = NormalOptions();
  options.viewpoint.x() = std::nan("");
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("viewpoint"), std::string::npos) << error;
  options = NormalOptions();
  options.axis_direction = Eigen::Vector3d::Zero();
  EXPECT_TRUE(options.IsValid(&error));  // the axis is not used towards a viewpoint
  options.orientation = NormalOrientation::kAwayFromAxis;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("axis_direction"), std::string::npos) << error;
  options.axis_direction = Eigen::Vector3d(0.0, 1e-200, 0.0);  // tiny but usable
  EXPECT_TRUE(options.IsValid(&error)) << error;
  options.orientation = NormalOrientation::kTowardsAxis;
  options.axis_point.z() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("axis_point"), std::string::npos) << error;
}

TEST(EstimateNormals, RejectsBadInput) {
  NormalOptions options;
  const Cloud two = cloud_of({{0, 0, 0}, {1, 0, 0}});
  EXPECT_THROW(estimate_normals(two, options), Error);
  const Cloud three = cloud_of({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  EXPECT_NO_THROW(estimate_normals(three, options));
  options.k = 0;
  try {
    estimate_normals(three, options);
    FAIL() << "k = 0 was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("k = 0"), std::string::npos) << e.what();
  }
  Cloud bad = three;
  bad.points[1].y = std::numeric_limits<float>::quiet_NaN();
  try {
    estimate_normals(bad, NormalOptions());
    FAIL() << "a NaN point was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("estimate_normals: nearest-neighbour search: 1 of 3 points are not finite"),
              std::string::npos)
        << e.what();
  }

  Mesh mesh = torus(20, 10, false);
  EXPECT_THROW(estimate_normals(mesh, 2), Error);
  mesh.faces.push_back({0, 1, static_cast<std::int32_t>(mesh.vertices.size())});
  EXPECT_THROW(estimate_normals(mesh, 16), Error);  // face index out of range
  mesh.faces.clear();
  EXPECT_THROW(estimate_normals(mesh, 16), Error);  // nothing to orient by
  Mesh small;
  small.vertices = {{0, 0, 0}, {1, 0, 0}};
  small.faces = {{0, 1, 1}};
  EXPECT_THROW(estimate_normals(small, 16), Error);
}

}  // namespace
}  // namespace conform
