// The C2 network of bicubic Bézier patches through a grid: exact interpolation, C1 and C2 across patch edges, the
// natural spline's slopes, closest points, fundamental forms; grid files' bad shapes and round trip.

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "conform/core/error.h"
#include "conform/fitting/bezier_network.h"
#include "conform/fitting/coons_patch.h"
#include "conform/fitting/surface_grid.h"
#include "wavy_grid.h"

namespace conform {
namespace {

using test::wavy;
using test::wavy_grid;

TEST(BezierNetwork, InterpolatesTheGridExactly) {
  const SurfaceGrid grid = wavy_grid(9, 12);
  const BezierNetwork net(grid);
  ASSERT_EQ(net.patch_rows(), 8);
  ASSERT_EQ(net.patch_cols(), 11);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) EXPECT_LT((net.position(c, r) - grid.at(r, c)).norm(), 1e-12);  // rounding
  }
}

TEST(BezierNetwork, IsC1AndC2AcrossPatchEdges) {
  const BezierNetwork net(wavy_grid(9, 12));
  double c1 = 0.0, c2 = 0.0;
  for (int r = 0; r < net.patch_rows(); ++r) {
    for (int c = 0; c + 1 < net.patch_cols(); ++c) {
      for (double s = 0.0; s <= 1.0; s += 0.125) {  // the edge u = c + 1 seen from both patches
        for (int dv = 0; dv <= 1; ++dv) {
          c1 = std::max(c1, (net.patch(r, c).derivative(1.0, s, 1, dv) - net.patch(r, c + 1).derivative(0.0, s, 1, dv)).norm());
        }
        c2 = std::max(c2, (net.patch(r, c).derivative(1.0, s, 2, 0) - net.patch(r, c + 1).derivative(0.0, s, 2, 0)).norm());
      }
    }
  }
  for (int r = 0; r + 1 < net.patch_rows(); ++r) {
    for (int c = 0; c < net.patch_cols(); ++c) {
      for (double s = 0.0; s <= 1.0; s += 0.125) {
        c1 = std::max(c1, (net.patch(r, c).derivative(s, 1.0, 0, 1) - net.patch(r + 1, c).derivative(s, 0.0, 0, 1)).norm());
        c2 = std::max(c2, (net.patch(r, c).derivative(s, 1.0, 0, 2) - net.patch(r + 1, c).derivative(s, 0.0, 0, 2)).norm());
      }
    }
  }
  // Tensor-product cubic spline: C2 up to rounding of slopes of a few mm per unit.
  EXPECT_LT(c1, 1e-11);
  EXPECT_LT(c2, 1e-10);
}

TEST(NaturalSpline, SlopesOfLinearDataAreExactAndEndsAreNatural) {
  std::vector<Eigen::Vector3d> line, bent;
  for (int k = 0; k < 7; ++k) line.emplace_back(2.0 * k, -k, 0.5), bent.emplace_back(k, k * k, 0.0);
  for (const Eigen::Vector3d& d : natural_spline_slopes(line)) EXPECT_LT((d - Eigen::Vector3d(2, -1, 0)).norm(), 1e-12);
  // The natural end: zero second derivative, i.e. 2 D0 + D1 = 3 (Q1 - Q0).
  const std::vector<Eigen::Vector3d> d = natural_spline_slopes(bent);
  EXPECT_LT((2.0 * d[0] + d[1] - 3.0 * (bent[1] - bent[0])).norm(), 1e-12);
  EXPECT_LT((d[2] + 4.0 * d[3] + d[4] - 3.0 * (bent[4] - bent[2])).norm(), 1e-12);
}

TEST(ProjectToSurface, FindsTheFootOfThePerpendicular) {
  const BezierNetwork net(wavy_grid(9, 12));
  const Eigen::Vector3d foot = net.position(4.3, 3.7);
  const Eigen::Vector3d p = foot + 0.8 * net.normal(4.3, 3.7);
  double u = 4.0, v = 4.0;
  ASSERT_TRUE(project_to_surface(net, p, &u, &v));
  EXPECT_NEAR(u, 4.3, 1e-9);  // Newton converges to rounding
  EXPECT_NEAR(v, 3.7, 1e-9);
}

TEST(FundamentalForms, SphereNormalCurvatureIsMinusOneOverR) {
  // A sphere cap z = sqrt(R^2 - x^2 - y^2) sampled finely: k_n = -1/R in every direction at the top (convex).
  SurfaceGrid grid;
  grid.rows = grid.cols = 21;
  for (int r = 0; r < 21; ++r) {
    for (int c = 0; c < 21; ++c) {
      const double x = c - 10.0, y = r - 10.0;
      grid.points.emplace_back(x, y, std::sqrt(2500.0 - x * x - y * y));
    }
  }
  const BezierNetwork net(grid);
  const FundamentalForms f = fundamental_forms(net, 10.0, 10.0);
  EXPECT_NEAR(f.normal_curvature(1.0, 0.0), -1.0 / 50.0, 1e-4);  // interpolation error of the spline, h = 1 mm
  EXPECT_NEAR(f.normal_curvature(1.0, 1.0), -1.0 / 50.0, 1e-4);
  EXPECT_NEAR(f.normal.z(), 1.0, 1e-9);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(text.c_str(), f);
  std::fclose(f);
  return path;
}

TEST(SurfaceGrid, HolesAndRaggedRowsAreNamed) {
  const std::string head = "row,col,x_mm,y_mm,z_mm\n";
  const std::string full = head + "0,0,0,0,0\n0,1,1,0,0\n1,0,0,1,0\n1,1,1,1,0\n";
  const SurfaceGrid grid = surface_grid_from_table(read_csv(write_temp("full.csv", full)));
  EXPECT_EQ(grid.rows, 2);
  EXPECT_EQ(grid.at(1, 1), Eigen::Vector3d(1, 1, 0));
  const std::string hole = head + "0,0,0,0,0\n0,1,1,0,0\n0,2,2,0,0\n1,0,0,1,0\n1,2,2,1,0\n";
  try {
    surface_grid_from_table(read_csv(write_temp("hole.csv", hole)));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hole.csv: hole in the grid: row 1, col 1"), std::string::npos) << e.what();
  }
  const std::string ragged = head + "0,0,0,0,0\n0,1,1,0,0\n0,2,2,0,0\n1,0,0,1,0\n1,1,1,1,0\n";
  try {
    surface_grid_from_table(read_csv(write_temp("ragged.csv", ragged)));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ragged.csv: ragged grid: row 1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(surface_grid_from_table(read_csv(write_temp("dup.csv", full + "1,1,1,1,0\n"))), Error);
  // Written and read back: the same grid (6 decimals hold these values exactly).
  surface_grid_table(grid).write(::testing::TempDir() + "again.csv");
  const SurfaceGrid again = surface_grid_from_table(read_csv(::testing::TempDir() + "again.csv"));
  EXPECT_EQ(again.points, grid.points);
}

}  // namespace
}  // namespace conform
