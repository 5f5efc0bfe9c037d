// The cylinder fit over the variations a jacket tube's scan really has: ovality (a in r = R + a cos 2 theta, D_max -
// D_min = 4a), peaking at the seam weld, partial arcs, noise, outliers, dense and coarse meshes, shop-frame
// coordinates far from the origin, the vertices (PCA normals) and the smooth surface's samples (as --points surface).
// The bound: the axis within max(0.05 mm, a / 4) of the truth and the radius within the same of the mean radius R, or
// the fit says it is doubtful (ok false, or a warning). Never a wrong cylinder that reports itself fine.
// Each case prints a [matrix] line with its figures.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/mesh_sampling.h"
#include "conform/core/phong_surface.h"
#include "tube_fit.h"

namespace conform {
namespace {

using test::errors;
using test::kDeg;

enum class Points { kVertices, kSurface };

struct Case {
  double radius_mm = 50.0;
  double length_mm = 100.0;
  double arc_deg = 360.0;
  double ovality_mm = 0.0;  // a
  double seam_mm = 0.0;
  double noise_mm = 0.02;
  double outliers = 0.0;
  int vertices = 3000;
  bool shop_frame = false;  // the axis 100 m from the origin, tilted
  Points points = Points::kVertices;
  std::uint64_t seed = 2;
};

struct Outcome {
  bool flagged = false;  // ok false or a warning
  bool within = false;   // axis and radius within the bound
};

Outcome run_case(const Case& c) {
  TubeOptions t;
  t.radius_mm = c.radius_mm;
  t.length_mm = c.length_mm;
  t.arc_rad = c.arc_deg * kDeg;
  t.arc_center_rad = 0.4;
  t.ovality_mm = c.ovality_mm;
  t.ovality_azimuth_rad = 0.3;
  t.seam_height_mm = c.seam_mm;
  t.seam_azimuth_rad = 0.9;
  t.noise_mm = c.noise_mm;
  t.outlier_fraction = c.outliers;
  t.vertex_count = c.vertices;
  t.seed = c.seed;
  if (c.shop_frame) t.T_world_tube = tube_frame({100000.0, 2500.0, -800.0}, {0.2, 1.0, 0.1}, {0.0, 0.0, 1.0});
  const TubeScan scan = generate_tube(t);
  std::vector<Eigen::Vector3d> points, normals;
  if (c.points == Points::kSurface) {
    const PhongSurface smooth(scan.mesh);
    MeshSurfaceSample s = sample_mesh_surface(scan.mesh, 20000, &smooth);
    points = std::move(s.points);
    normals = std::move(s.normals);
  } else {
    points = scan.mesh.vertices;
    normals = estimate_normals(scan.mesh, 16);
  }
  const CylinderFitResult fit = fit_cylinder(points, normals, CylinderFitOptions{});
  const test::CylinderErrors e = errors(fit, scan.truth, c.radius_mm);
  const double bound = std::max(0.05, c.ovality_mm / 4.0);
  Outcome out;
  out.flagged = !fit.ok || !fit.warnings.empty();
  out.within = std::abs(e.radius_mm) <= bound && e.offset_mm <= bound;
  std::printf(
      "[matrix] R %5.0f arc %3.0f a %.2f seam %.1f noise %.2f out %.2f n %5d %s %-8s seed %llu | dr %+.4f offset "
      "%.4f (bound %.3f) inliers %5.1f%% arc %5.1f shape %.3f | %s%s\n",
      c.radius_mm, c.arc_deg, c.ovality_mm, c.seam_mm, c.noise_mm, c.outliers, c.vertices, c.shop_frame ? "shop" : "orig",
      c.points == Points::kSurface ? "surface" : "vertices", static_cast<unsigned long long>(c.seed), e.radius_mm,
      e.offset_mm, bound, 100.0 * fit.inlier_fraction, fit.arc_rad / kDeg, fit.shape_deviation_mm,
      fit.ok ? "ok" : fit.termination.c_str(), fit.warnings.empty() ? "" : " +warning");
  return out;
}

// Every case: within the bound, or flagged. `must_be_within`: a closed or wide arc, whose mean circle the data define,
// must be found, not merely flagged.
void expect_matrix(const std::vector<Case>& cases, bool must_be_within) {
  for (const Case& c : cases) {
    SCOPED_TRACE("R " + std::to_string(c.radius_mm) + " arc " + std::to_string(c.arc_deg) + " a " +
                 std::to_string(c.ovality_mm) + " seed " + std::to_string(c.seed));
    const Outcome o = run_case(c);
    if (must_be_within) {
      EXPECT_TRUE(o.within && !o.flagged);
    } else {
      EXPECT_TRUE(o.within || o.flagged);
    }
  }
}

// The lead's case (R 50, 3000 vertices, --points surface gave a 233 deg arc, the axis 0.37 mm off) and its
// neighbours: every closed oval tube must give its mean circle.
TEST(FitCylinderMatrix, OvalClosedTubes) {
  std::vector<Case> cases;
  for (double a : {0.0, 0.2, 0.5, 2.0}) {
    for (double noise : {0.02, 0.3}) {
      for (Points p : {Points::kVertices, Points::kSurface}) {
        for (std::uint64_t seed : {2u, 3u}) {
          Case c;
          c.ovality_mm = a;
          c.noise_mm = noise;
          c.points = p;
          c.seed = seed;
          cases.push_back(c);
        }
      }
    }
  }
  expect_matrix(cases, true);
}

// Seam peaking (2 mm over 20 mm) and 2% outliers on oval tubes, dense and coarse, in shop coordinates: the seam and the
// outliers stay out, the tube's mean circle comes out.
TEST(FitCylinderMatrix, SeamOutliersShopFrame) {
  std::vector<Case> cases;
  for (int vertices : {3000, 20000}) {
    for (Points p : {Points::kVertices, Points::kSurface}) {
      for (double a : {0.2, 1.0}) {
        Case c;
        c.radius_mm = 150.0;
        c.length_mm = 200.0;
        c.ovality_mm = a;
        c.seam_mm = 2.0;
        c.noise_mm = 0.05;
        c.outliers = p == Points::kVertices ? 0.02 : 0.0;  // surface samples of a mesh with spikes: not a scan
        c.vertices = vertices;
        c.shop_frame = true;
        c.points = p;
        c.seed = 5;
        cases.push_back(c);
      }
    }
  }
  expect_matrix(cases, true);
}

// Larger tubes with ovality as a share of the diameter (0.5% and 1% of D: D_max - D_min = 4a).
TEST(FitCylinderMatrix, OvalityPercentOfDiameter) {
  std::vector<Case> cases;
  for (double pct : {0.5, 1.0}) {
    for (Points p : {Points::kVertices, Points::kSurface}) {
      Case c;
      c.radius_mm = 500.0;
      c.length_mm = 400.0;
      c.ovality_mm = pct / 100.0 * 1000.0 / 4.0;
      c.noise_mm = 0.1;
      c.vertices = 20000;
      c.shop_frame = true;
      c.points = p;
      c.seed = 7;
      cases.push_back(c);
    }
  }
  expect_matrix(cases, true);
}

// Partial arcs of oval tubes: a short arc does not define the mean circle of an oval section (it measures the local
// curvature), so the fit may only be within the bound or say it is doubtful. And a seam inside a round patch.
TEST(FitCylinderMatrix, PartialArcs) {
  std::vector<Case> cases;
  for (double arc : {120.0, 180.0, 240.0, 300.0}) {
    for (double a : {0.0, 0.5}) {
      for (Points p : {Points::kVertices, Points::kSurface}) {
        Case c;
        c.arc_deg = arc;
        c.ovality_mm = a;
        c.noise_mm = 0.05;
        c.points = p;
        c.seed = 3;
        cases.push_back(c);
      }
    }
  }
  // A 2 mm seam inside a round patch with 2% outliers: left out, not widened into.
  for (double arc : {120.0, 240.0}) {
    Case c;
    c.arc_deg = arc;
    c.seam_mm = 2.0;
    c.outliers = 0.02;
    c.noise_mm = 0.05;
    c.seed = 4;
    cases.push_back(c);
  }
  expect_matrix(cases, false);
}

}  // namespace
}  // namespace conform
