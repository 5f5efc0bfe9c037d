// The shape figures of a cylinder fit (shape_deviation_mm, hidden_ovality_mm, shape_*_ambiguity_mm, warnings) on
// generated oval tubes (r = R + a cos 2(theta - theta0)) against the generator's truth.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "tube_fit.h"

namespace conform {
namespace {

using test::errors;
using test::kDeg;

struct Fitted {
  CylinderFitResult fit;
  test::CylinderErrors error;
};

Fitted fit_tube(double arc_deg, double ovality_mm, const CylinderFitOptions& options = {}) {
  TubeOptions t;
  t.radius_mm = 50.0;
  t.length_mm = 100.0;
  t.arc_rad = arc_deg * kDeg;
  t.arc_center_rad = 0.4;
  t.ovality_mm = ovality_mm;
  t.ovality_azimuth_rad = 0.3;
  t.noise_mm = 0.02;
  t.vertex_count = 3000;
  t.seed = 2;
  const TubeScan scan = generate_tube(t);
  Fitted f;
  f.fit = fit_cylinder(scan.mesh.vertices, estimate_normals(scan.mesh, 16), options);
  f.error = errors(f.fit, scan.truth, t.radius_mm);
  return f;
}

// Over the full turn the profile shows the ovality itself (the mean circle absorbs none of cos 2 theta) and nothing
// is ambiguous. Tolerance: 10% of a (5 deg bins see the peak within cos(5 deg); the fit's error, noise 0.02 mm).
TEST(CylinderShape, FullOvalTubeShowsItsOvality) {
  const Fitted f = fit_tube(360.0, 0.5);
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  EXPECT_NEAR(f.fit.shape_deviation_mm, 0.5, 0.05);
  EXPECT_LT(f.fit.shape_axis_ambiguity_mm, 0.01);
  EXPECT_LT(f.fit.shape_radius_ambiguity_mm, 0.01);
  EXPECT_TRUE(f.fit.warnings.empty());
  EXPECT_LE(f.error.offset_mm, 0.02);
  EXPECT_LE(std::abs(f.error.radius_mm), 0.02);
}

TEST(CylinderShape, RoundFullTubeHasNoShape) {
  const Fitted f = fit_tube(360.0, 0.0);
  ASSERT_TRUE(f.fit.ok) << f.fit.termination;
  EXPECT_LT(f.fit.shape_deviation_mm, 0.01);
  EXPECT_TRUE(f.fit.warnings.empty());
}

// Arcs of an oval tube: the circle hugs the local curvature, off the mean circle by up to several times a. The
// ambiguity is the first-order effect of the ovality the residuals show (or could hide), at the worst of 16 phases:
// it must match the real error to within 25% (first order in a / R, and the phase grid), and the fit must warn.
TEST(CylinderShape, PartialArcAmbiguityMatchesTheOvalError) {
  for (double arc : {120.0, 240.0}) {
    const Fitted f = fit_tube(arc, 0.5);
    ASSERT_TRUE(f.fit.ok) << f.fit.termination;
    EXPECT_GT(f.error.offset_mm, 0.1) << arc;  // the case is a real one: the fit is off the mean circle
    EXPECT_GE(f.fit.shape_axis_ambiguity_mm, 0.75 * f.error.offset_mm) << arc;
    EXPECT_LE(f.fit.shape_axis_ambiguity_mm, 2.0 * f.error.offset_mm) << arc;
    EXPECT_GE(f.fit.shape_radius_ambiguity_mm, 0.75 * std::abs(f.error.radius_mm)) << arc;
    EXPECT_FALSE(f.fit.warnings.empty()) << arc;
  }
}

// The warning's limit is an option: above the ambiguity, silent.
TEST(CylinderShape, AmbiguityWarningFollowsTheOption) {
  CylinderFitOptions o;
  o.max_shape_ambiguity_mm = 1e6;
  EXPECT_TRUE(fit_tube(120.0, 0.0, o).fit.warnings.empty());
  o.max_shape_ambiguity_mm = 0.0;
  EXPECT_FALSE(fit_tube(120.0, 0.0, o).fit.warnings.empty());
  o.max_shape_ambiguity_mm = -1.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
}

}  // namespace
}  // namespace conform
