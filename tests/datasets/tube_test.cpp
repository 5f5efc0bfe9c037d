#include "conform/datasets/tube.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kDeg = M_PI / 180.0;

// A pose far from the identity, so that frame mistakes show.
Eigen::Isometry3d skew_pose() { return tube_frame({1200.0, -350.0, 800.0}, {1.0, 2.0, -0.5}, {0.0, 0.0, 1.0}); }

// A vertex in the tube frame of the truth.
Eigen::Vector3d in_tube(const TubeTruth& truth, const Eigen::Vector3d& p_world) {
  return truth.T_world_tube.inverse() * p_world;
}

double azimuth(const Eigen::Vector3d& p_tube) { return std::atan2(p_tube.y(), p_tube.x()); }

// Least-squares fit of r = R + c cos 2 theta + s sin 2 theta; returns (a, theta0) with a cos 2(theta - theta0).
std::pair<double, double> fit_ovality(const TubeScan& scan) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(scan.mesh.vertices.size()), 3);
  Eigen::VectorXd b(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const Eigen::Vector3d p = in_tube(scan.truth, scan.mesh.vertices[static_cast<std::size_t>(i)]);
    const double theta = azimuth(p);
    A.row(i) << 1.0, std::cos(2.0 * theta), std::sin(2.0 * theta);
    b(i) = p.head<2>().norm();
  }
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(b);
  return {std::hypot(x(1), x(2)), 0.5 * std::atan2(x(2), x(1))};
}

// Radial residuals r - R of all vertices (tube frame, no bow).
std::vector<double> radial_residuals(const TubeScan& scan) {
  std::vector<double> out;
  for (const Eigen::Vector3d& v : scan.mesh.vertices) {
    out.push_back(in_tube(scan.truth, v).head<2>().norm() - scan.truth.radius_mm);
  }
  return out;
}

std::pair<double, double> mean_and_std(const std::vector<double>& values) {
  double sum = 0.0;
  for (double v : values) sum += v;
  const double mean = sum / static_cast<double>(values.size());
  double sq = 0.0;
  for (double v : values) sq += (v - mean) * (v - mean);
  return {mean, std::sqrt(sq / static_cast<double>(values.size() - 1))};
}

std::vector<double> edge_lengths(const Mesh& mesh) {
  std::set<std::pair<std::int32_t, std::int32_t>> edges;
  for (const Face& f : mesh.faces) {
    for (int i = 0; i < 3; ++i)
      edges.insert(std::minmax(f[static_cast<std::size_t>(i)], f[static_cast<std::size_t>((i + 1) % 3)]));
  }
  std::vector<double> lengths;
  for (const auto& e : edges) {
    lengths.push_back(
        (mesh.vertices[static_cast<std::size_t>(e.first)] - mesh.vertices[static_cast<std::size_t>(e.second)]).norm());
  }
  return lengths;
}

TEST(Tube, UndeformedNoiseFreeVerticesLieOnTheCylinderInTheWorldFrame) {
  for (double arc_deg : {360.0, 75.0}) {
    TubeOptions options;
    options.radius_mm = 500.0;
    options.length_mm = 400.0;
    options.arc_rad = arc_deg * kDeg;
    options.arc_center_rad = 100.0 * kDeg;
    options.edge_mm = 10.0;
    options.T_world_tube = skew_pose();
    const TubeScan scan = generate_tube(options);
    const Eigen::Vector3d a = scan.truth.axis_point;
    const Eigen::Vector3d d = scan.truth.axis_direction;
    ASSERT_NEAR(d.norm(), 1.0, 1e-15);
    double worst_radius = 0.0;
    double worst_axial = 0.0;
    for (const Eigen::Vector3d& v : scan.mesh.vertices) {
      const double along = (v - a).dot(d);
      worst_radius = std::max(worst_radius, std::abs(((v - a) - along * d).norm() - 500.0));
      worst_axial = std::max(worst_axial, std::abs(along) - 200.0);
    }
    std::printf("[ measured ] arc %.0f deg: %zu vertices, worst |distance to axis - R| = %.3g mm\n", arc_deg,
                scan.mesh.vertices.size(), worst_radius);
    EXPECT_LT(worst_radius, 1e-9);
    EXPECT_LT(worst_axial, 1e-9);
    EXPECT_EQ(static_cast<std::int64_t>(scan.mesh.vertices.size()), scan.truth.grid.vertex_count());
    EXPECT_EQ(static_cast<std::int64_t>(scan.mesh.faces.size()), scan.truth.grid.face_count());
    EXPECT_EQ(scan.mesh.vertices, scan.truth.exact_vertices);
  }
}

TEST(Tube, PatchCoversItsAzimuthRangeAndAClosedTubeHasNoSeamOfVertices) {
  TubeOptions options;
  options.arc_rad = 60.0 * kDeg;
  options.arc_center_rad = -30.0 * kDeg;
  const TubeScan patch = generate_tube(options);
  double lo = 1e9;
  double hi = -1e9;
  for (const Eigen::Vector2d& p : patch.truth.vertex_parameters) {
    lo = std::min(lo, p.x());
    hi = std::max(hi, p.x());
  }
  EXPECT_NEAR(lo, -60.0 * kDeg, 1e-12);
  EXPECT_NEAR(hi, 0.0, 1e-12);

  options.arc_rad = 2.0 * M_PI;
  const TubeScan tube = generate_tube(options);
  // Closed and manifold: every edge is shared by exactly two faces, only the two end rings are borders.
  std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
  for (const Face& f : tube.mesh.faces) {
    for (int i = 0; i < 3; ++i)
      ++uses[std::minmax(f[static_cast<std::size_t>(i)], f[static_cast<std::size_t>((i + 1) % 3)])];
  }
  int border = 0;
  for (const auto& [edge, count] : uses) {
    EXPECT_LE(count, 2);
    border += count == 1 ? 1 : 0;
  }
  EXPECT_EQ(border, 2 * tube.truth.grid.columns);
}

TEST(Tube, OvalityAmplitudeMeasuredFromANoisyMeshMatchesTheParameter) {
  TubeOptions options;
  options.radius_mm = 150.0;
  options.edge_mm = 3.0;
  options.ovality_mm = 0.8;
  options.ovality_azimuth_rad = 25.0 * kDeg;
  options.noise_mm = 0.05;
  options.T_world_tube = skew_pose();
  const TubeScan scan = generate_tube(options);
  const auto [a, theta0] = fit_ovality(scan);
  // The fit's standard error is about sigma * sqrt(2 / N) = 0.05 * sqrt(2 / 31000) = 4e-4 mm.
  std::printf("[ measured ] ovality %.5f mm at %.3f deg (parameter 0.8 mm at 25 deg), N = %zu\n", a, theta0 / kDeg,
              scan.mesh.vertices.size());
  EXPECT_NEAR(a, 0.8, 0.003);
  EXPECT_NEAR(theta0 / kDeg, 25.0, 0.2);

  options.noise_mm = 0.0;
  const auto [exact_a, exact_theta0] = fit_ovality(generate_tube(options));
  EXPECT_NEAR(exact_a, 0.8, 1e-9);
  EXPECT_NEAR(exact_theta0, 25.0 * kDeg, 1e-9);
}

TEST(Tube, SeamRidgeHasItsHeightAtTheSeamAzimuthAndItsWidth) {
  for (double height : {0.5, -0.3}) {
    TubeOptions options;
    options.radius_mm = 150.0;
    options.arc_rad = 90.0 * kDeg;
    options.arc_center_rad = 40.0 * kDeg;
    options.edge_mm = 1.0;
    options.seam_height_mm = height;
    options.seam_width_mm = 30.0;
    options.seam_azimuth_rad = 47.0 * kDeg;
    const TubeScan scan = generate_tube(options);
    const std::vector<double> dr = radial_residuals(scan);
    std::size_t peak = 0;
    double above_half = 0.0;  // arc length where the ridge is beyond half its height: w / 2 for a raised cosine
    for (std::size_t i = 0; i < dr.size(); ++i) {
      if (std::abs(dr[i]) > std::abs(dr[peak])) peak = i;
      const double s = 150.0 * (scan.truth.vertex_parameters[i].x() - 47.0 * kDeg);
      if (std::abs(s) >= 15.0) {
        EXPECT_NEAR(dr[i], 0.0, 1e-9) << "outside the ridge";
      }
      if (std::abs(dr[i]) > 0.5 * std::abs(height)) above_half = std::max(above_half, 2.0 * std::abs(s));
    }
    const double peak_azimuth = scan.truth.vertex_parameters[peak].x() / kDeg;
    std::printf("[ measured ] seam %.4f mm (parameter %.1f) at %.3f deg (47), half-height width %.2f mm (15)\n",
                dr[peak], height, peak_azimuth, above_half);
    // The nearest vertex is within a quarter column (0.25 mm) of the crest: cos(2 pi 0.25 / 30) loses < 0.1%.
    EXPECT_NEAR(dr[peak], height, 0.001 * std::abs(height));
    EXPECT_NEAR(peak_azimuth, 47.0, 0.25 / 150.0 / kDeg + 1e-9);
    EXPECT_NEAR(above_half, 15.0, 1.0);  // within one column of the vertices
  }
}

TEST(Tube, BumpsAndIndentationsHaveTheirHeightsAndFootprints) {
  TubeOptions options;
  options.radius_mm = 200.0;
  options.length_mm = 300.0;
  options.edge_mm = 1.5;
  options.bumps = {{30.0 * kDeg, 20.0, 1.2, 25.0}, {200.0 * kDeg, -60.0, -0.7, 15.0}};
  options.T_world_tube = skew_pose();
  const TubeScan scan = generate_tube(options);
  const std::vector<double> dr = radial_residuals(scan);
  for (const TubeBump& bump : options.bumps) {
    double extreme = 0.0;
    for (std::size_t i = 0; i < dr.size(); ++i) {
      const Eigen::Vector2d& p = scan.truth.vertex_parameters[i];
      const double d = std::hypot(200.0 * wrap_angle(p.x() - bump.azimuth_rad), p.y() - bump.z_mm);
      if (d >= bump.radius_mm) continue;
      if (std::abs(dr[i]) > std::abs(extreme)) extreme = dr[i];
    }
    std::printf("[ measured ] bump %.4f mm (parameter %.2f)\n", extreme, bump.height_mm);
    // A vertex lies within one edge length of the centre: the raised cosine keeps > 97% of its height there.
    EXPECT_NEAR(extreme, bump.height_mm, 0.03 * std::abs(bump.height_mm));
  }
  std::size_t untouched = 0;
  for (double v : dr) untouched += std::abs(v) < 1e-9 ? 1 : 0;
  const double bump_area = M_PI * (25.0 * 25.0 + 15.0 * 15.0);
  const double share = 1.0 - bump_area / (2.0 * M_PI * 200.0 * 300.0);
  EXPECT_NEAR(static_cast<double>(untouched) / static_cast<double>(dr.size()), share, 0.002);
}

TEST(Tube, BowMovesTheMiddleBySagittaTowardsItsAzimuth) {
  TubeOptions options;
  options.radius_mm = 100.0;
  options.length_mm = 1000.0;
  options.edge_mm = 8.0;
  options.bow_mm = 3.0;
  options.bow_azimuth_rad = 60.0 * kDeg;
  options.T_world_tube = skew_pose();
  const TubeScan scan = generate_tube(options);
  // Ring centres: the mean of a ring of equally spaced vertices is its centre. Fit c(z) = s (1 - (2z/L)^2) u.
  std::map<double, std::pair<Eigen::Vector2d, int>> rings;
  for (std::size_t i = 0; i < scan.mesh.vertices.size(); ++i) {
    // Eigen vectors start uninitialised: insert a zero sum explicitly.
    auto& ring = rings.try_emplace(scan.truth.vertex_parameters[i].y(), Eigen::Vector2d::Zero(), 0).first->second;
    ring.first += in_tube(scan.truth, scan.mesh.vertices[i]).head<2>();
    ring.second += 1;
  }
  Eigen::Vector2d num = Eigen::Vector2d::Zero();
  double den = 0.0;
  for (const auto& [z, ring] : rings) {
    const double shape = 1.0 - std::pow(2.0 * z / 1000.0, 2);
    num += shape * ring.first / ring.second;
    den += shape * shape;
  }
  const Eigen::Vector2d sagitta = num / den;
  std::printf("[ measured ] bow %.9f mm towards %.6f deg (parameter 3 mm, 60 deg)\n", sagitta.norm(),
              std::atan2(sagitta.y(), sagitta.x()) / kDeg);
  EXPECT_NEAR(sagitta.norm(), 3.0, 1e-9);
  EXPECT_NEAR(std::atan2(sagitta.y(), sagitta.x()), 60.0 * kDeg, 1e-9);
  // The ends stay on the straight axis.
  EXPECT_LT(tube_bow_offset(options, 500.0).norm(), 1e-12);
}

TEST(Tube, FacesPointAwayFromTheAxisOutsideAndTowardsItInside) {
  for (TubeSurface surface : {TubeSurface::kOuter, TubeSurface::kInner}) {
    TubeOptions options;
    options.surface = surface;
    options.ovality_mm = 1.0;
    options.seam_height_mm = 0.5;
    options.T_world_tube = skew_pose();
    const TubeScan scan = generate_tube(options);
    const double sign = surface == TubeSurface::kOuter ? 1.0 : -1.0;
    double worst = 1.0;
    for (std::size_t f = 0; f < scan.mesh.faces.size(); ++f) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (std::int32_t v : scan.mesh.faces[f]) c += scan.mesh.vertices[static_cast<std::size_t>(v)] / 3.0;
      const Eigen::Vector3d p = in_tube(scan.truth, c);
      const Eigen::Vector3d radial = scan.truth.T_world_tube.linear() * Eigen::Vector3d(p.x(), p.y(), 0.0).normalized();
      worst = std::min(worst, sign * face_normal(scan.mesh, f).dot(radial));
    }
    EXPECT_GT(worst, 0.99) << (surface == TubeSurface::kOuter ? "outer" : "inner");
    // The analytic normal agrees with the winding.
    const TubeSurfacePoint s = tube_surface(options, 0.3, 10.0);
    EXPECT_GT(sign * s.normal.dot(options.T_world_tube.linear() * Eigen::Vector3d(std::cos(0.3), std::sin(0.3), 0)),
              0.99);
  }
}

TEST(Tube, AnalyticNormalIsTheCrossProductOfTheSurfaceTangents) {
  TubeOptions options;
  options.ovality_mm = 2.0;
  options.ovality_azimuth_rad = 0.4;
  options.seam_height_mm = 1.5;
  options.seam_width_mm = 40.0;
  options.seam_azimuth_rad = 0.2;
  options.bumps = {{0.1, 20.0, 3.0, 30.0}};
  options.bow_mm = 5.0;
  options.bow_azimuth_rad = 1.0;
  options.T_world_tube = skew_pose();
  const double h = 1e-6;
  for (double theta : {0.05, 0.15, 0.25, 0.35}) {
    for (double z : {5.0, 20.0, 33.0, 140.0}) {
      const Eigen::Vector3d dt =
          (tube_surface(options, theta + h, z).point - tube_surface(options, theta - h, z).point);
      const Eigen::Vector3d dz =
          (tube_surface(options, theta, z + h).point - tube_surface(options, theta, z - h).point);
      const Eigen::Vector3d expected = dt.cross(dz).normalized();
      EXPECT_LT((tube_surface(options, theta, z).normal - expected).norm(), 1e-6) << theta << " " << z;
    }
  }
}

TEST(Tube, EdgesAreNearTheTargetLength) {
  for (double arc_deg : {360.0, 60.0}) {
    TubeOptions options;
    options.radius_mm = 300.0;
    options.length_mm = 250.0;
    options.arc_rad = arc_deg * kDeg;
    options.edge_mm = 4.0;
    const TubeScan scan = generate_tube(options);
    const std::vector<double> lengths = edge_lengths(scan.mesh);
    const auto [mean, sd] = mean_and_std(lengths);
    const auto near = std::count_if(lengths.begin(), lengths.end(), [](double l) { return std::abs(l - 4.0) < 0.4; });
    const double share = static_cast<double>(near) / static_cast<double>(lengths.size());
    const double shortest = *std::min_element(lengths.begin(), lengths.end());
    const double longest = *std::max_element(lengths.begin(), lengths.end());
    std::printf("[ measured ] arc %.0f: edges mean %.4f sd %.4f min %.4f max %.4f mm, %.2f%% within 10%% of 4 mm\n",
                arc_deg, mean, sd, shortest, longest, 100.0 * share);
    EXPECT_NEAR(mean, 4.0, arc_deg == 360.0 ? 0.08 : 0.2);
    EXPECT_GT(share, arc_deg == 360.0 ? 0.999 : 0.95);
    // A patch's straight borders need half-column edges; nothing shorter.
    EXPECT_GT(shortest, arc_deg == 360.0 ? 3.6 : 1.9);
    EXPECT_LT(longest, 4.4);
  }
}

}  // namespace
}  // namespace conform
