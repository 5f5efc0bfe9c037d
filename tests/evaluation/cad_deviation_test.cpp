// to_exact_cad_faces against a hand-made CAD reference: a cylinder's side (R 20 mm, 40 mm long) tessellated with 12
// segments, whose chords lie up to 20 (1 - cos 15 deg) = 0.68 mm inside it, and its analytic face.

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/evaluation/cad_deviation.h"

namespace conform {
namespace {

constexpr double kRadius = 20.0, kHalfLength = 20.0;
constexpr int kSegments = 12;

CadFaces tessellated_cylinder() {
  CadFaces cad;
  for (int k = 0; k < kSegments; ++k) {
    const double a = 2.0 * M_PI * k / kSegments;
    for (const double z : {-kHalfLength, kHalfLength}) {
      cad.mesh.vertices.emplace_back(kRadius * std::cos(a), kRadius * std::sin(a), z);
    }
  }
  for (int k = 0; k < kSegments; ++k) {
    const int a = 2 * k, b = 2 * ((k + 1) % kSegments);
    cad.mesh.faces.push_back({a, b, b + 1});  // outward: counter-clockwise seen from outside
    cad.mesh.faces.push_back({a, b + 1, a + 1});
  }
  cad.triangle_face.assign(cad.mesh.faces.size(), 0);
  CadFace side;
  side.type = CadSurfaceType::kCylinder;
  side.sense = 1;
  side.origin_mm = Eigen::Vector3d::Zero();
  side.axis = Eigen::Vector3d::UnitZ();
  side.radius_mm = kRadius;
  cad.faces.push_back(side);
  return cad;
}

Eigen::Vector3d at(double radius, double angle_deg, double z) {
  const double a = angle_deg * M_PI / 180.0;
  return {radius * std::cos(a), radius * std::sin(a), z};
}

TEST(CadDeviation, PointsOnTheFaceReadZeroWhereTheChordsReadUpToTheirSagitta) {
  const CadFaces cad = tessellated_cylinder();
  const double sagitta = kRadius * (1.0 - std::cos(M_PI / kSegments));
  std::vector<Eigen::Vector3d> scan;
  for (int i = 0; i < 90; ++i) scan.push_back(at(kRadius, 4.0 * i + 1.0, -15.0 + i % 30));
  scan.push_back(at(kRadius + 1.0, 7.5, 0.0));  // 1 mm outside, mid-chord
  scan.push_back(at(kRadius - 0.5, 0.0, 3.0));  // 0.5 mm inside, on a vertex line
  DeviationOptions flat;
  flat.smooth_surface = false;
  DeviationResult d = compute_deviation(scan, cad.mesh, flat);
  double worst_mesh = 0.0;
  for (int i = 0; i < 90; ++i) worst_mesh = std::max(worst_mesh, std::abs(d.deviation_mm[static_cast<std::size_t>(i)]));
  EXPECT_GT(worst_mesh, 0.9 * sagitta);  // the chords' error, as the tessellation gives it
  const std::size_t exact = to_exact_cad_faces(scan, cad, 2.0 * sagitta, d);
  EXPECT_EQ(exact, scan.size());
  for (int i = 0; i < 90; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_NEAR(d.deviation_mm[k], 0.0, 1e-12) << i;
    EXPECT_LT((d.closest[k] - scan[k]).norm(), 1e-12);
  }
  EXPECT_NEAR(d.deviation_mm[90], 1.0, 1e-12);
  EXPECT_NEAR(d.deviation_mm[91], -0.5, 1e-12);
  EXPECT_NEAR(d.closest[90].head<2>().norm(), kRadius, 1e-12);  // the foot on the exact surface
}

TEST(CadDeviation, BeyondTheFacesTrimTheTessellationIsKept) {
  const CadFaces cad = tessellated_cylinder();
  // 5 mm past the end, on the cylinder's extension: the untrimmed surface says 0, the part's rim 5 mm.
  const std::vector<Eigen::Vector3d> scan = {at(kRadius, 0.0, kHalfLength + 5.0)};
  DeviationResult d = compute_deviation(scan, cad.mesh, {});
  const double on_mesh = d.deviation_mm[0];
  EXPECT_NEAR(std::abs(on_mesh), 5.0, 1e-9);
  EXPECT_EQ(to_exact_cad_faces(scan, cad, 1.4, d), 0u);
  EXPECT_EQ(d.deviation_mm[0], on_mesh);
}

TEST(CadDeviation, UnmatchedPointsOtherSurfacesAndBadInput) {
  CadFaces cad = tessellated_cylinder();
  const std::vector<Eigen::Vector3d> scan = {at(kRadius, 7.5, 0.0), at(200.0, 0.0, 0.0)};
  DeviationOptions limited;
  limited.max_distance_mm = 10.0;
  DeviationResult d = compute_deviation(scan, cad.mesh, limited);
  ASSERT_TRUE(std::isnan(d.deviation_mm[1]));
  EXPECT_EQ(to_exact_cad_faces(scan, cad, 1.4, d), 1u);
  EXPECT_TRUE(std::isnan(d.deviation_mm[1]));  // unmatched stays unmatched
  cad.faces[0].type = CadSurfaceType::kBSpline;  // no analytic surface: the tessellation's figure stays
  DeviationResult b = compute_deviation(scan, cad.mesh, limited);
  const double kept = b.deviation_mm[0];
  EXPECT_EQ(to_exact_cad_faces(scan, cad, 1.4, b), 0u);
  EXPECT_EQ(b.deviation_mm[0], kept);
  EXPECT_THROW(to_exact_cad_faces(scan, cad, -1.0, b), Error);
  EXPECT_THROW(to_exact_cad_faces({scan[0]}, cad, 1.0, b), Error);
}

}  // namespace
}  // namespace conform
