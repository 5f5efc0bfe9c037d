// The projection model (Béarée et al. 2010, section 2.2) on a scan that is the nominal plane plus a known parabola
// along the plane's long axis: the fitted height and the mapped points recover it; the spline fits it as well.

#include "conform/compensation/projection_model.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kA = 2e-5;  // mm^-1: z = a u^2 rises 0.8 mm at u = 200 mm

// A flat nominal band around an ellipse (200 x 100 mm semi-axes) in z = 0, and the contour.
struct Flat {
  Polyline contour;
  Mesh surface;
};

Flat flat() {
  Flat f;
  f.contour.closed = true;
  for (int i = 0; i < 720; ++i) {
    const double t = 2 * M_PI * i / 720;
    f.contour.points.emplace_back(200 * std::cos(t), 100 * std::sin(t), 0);
  }
  const int n = 60;  // a 480 x 280 mm grid, 8 mm cells
  for (int j = 0; j <= 35; ++j) {
    for (int i = 0; i <= n; ++i) f.surface.vertices.emplace_back(-240 + 8.0 * i, -140 + 8.0 * j, 0);
  }
  for (int j = 0; j < 35; ++j) {
    for (int i = 0; i < n; ++i) {
      const auto v = [&](int a, int b) { return static_cast<std::int32_t>(b * (n + 1) + a); };
      f.surface.faces.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      f.surface.faces.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  }
  return f;
}

std::vector<Eigen::Vector3d> deformed_scan() {
  std::vector<Eigen::Vector3d> scan;
  for (int i = 0; i < 720; ++i) {
    const double t = 2 * M_PI * i / 720;
    for (double d = 1.0; d <= 9.0; d += 2.0) {  // a band outside the contour
      const double x = (200 + d) * std::cos(t), y = (100 + d) * std::sin(t);
      scan.emplace_back(x, y, kA * x * x);
    }
  }
  return scan;
}

TEST(ProjectionModel, ParabolaRecoversTheHeightField) {
  const Flat f = flat();
  const IcpReference nominal(f.surface);
  const ProjectionModel m =
      fit_projection_model(f.contour, nominal, deformed_scan(), Eigen::Isometry3d::Identity(), {});
  EXPECT_GT(m.samples, 3000u);
  EXPECT_NEAR(std::abs(m.u_axis.x()), 1.0, 1e-9);  // the principal direction is the ellipse's long axis
  // Exact model, exact data: to the fit's rounding (the pairs are exact on the flat triangles).
  EXPECT_LT(m.rms_mm, 1e-9);
  for (double x : {-190.0, -50.0, 0.0, 120.0, 195.0}) {
    const Eigen::Vector3d p = m.map_point(Eigen::Vector3d(x, 30.0, 0.0));
    EXPECT_NEAR(p.z(), kA * x * x, 1e-9);
    EXPECT_NEAR(p.x(), x, 1e-12);  // the height is along the plane's normal only
    const Eigen::Vector3d n = m.map_normal(Eigen::Vector3d(x, 30.0, 0.0), Eigen::Vector3d::UnitZ());
    EXPECT_LT((n - Eigen::Vector3d(-2 * kA * x, 0, 1).normalized()).norm(), 1e-9);
  }
}

TEST(ProjectionModel, SplineFitsTheSameField) {
  const Flat f = flat();
  const IcpReference nominal(f.surface);
  ProjectionOptions o;
  o.fit = ProjectionFit::kThinPlateSpline;
  const ProjectionModel m = fit_projection_model(f.contour, nominal, deformed_scan(), Eigen::Isometry3d::Identity(), o);
  // A smoothed spline is not exact for a parabola: within 1% of its 0.8 mm range along the contour.
  for (int i = 0; i < 36; ++i) {
    const double t = 2 * M_PI * i / 36;
    const Eigen::Vector3d p(205 * std::cos(t), 105 * std::sin(t), 0.0);
    EXPECT_NEAR(m.map_point(p).z(), kA * p.x() * p.x(), 0.008);
  }
}

TEST(ProjectionModel, TooFewSamplesOrBadOptionsThrow) {
  const Flat f = flat();
  const IcpReference nominal(f.surface);
  EXPECT_THROW(fit_projection_model(f.contour, nominal, {{0, 0, 0}}, Eigen::Isometry3d::Identity(), {}), Error);
  ProjectionOptions o;
  o.spline_centres = 2;
  EXPECT_THROW(fit_projection_model(f.contour, nominal, deformed_scan(), Eigen::Isometry3d::Identity(), o), Error);
}

}  // namespace
}  // namespace conform
