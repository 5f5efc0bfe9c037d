// The degeneracy report (registration/degeneracy.h): a tube patch is degenerate along and about its axis, a plane in
// its three in-plane motions, a sphere in its three rotations about the centre; the box part with features is not.

#include "conform/registration/degeneracy.h"

#include <gtest/gtest.h>

#include "conform/datasets/parts.h"
#include "conform/datasets/tube.h"
#include "conform/registration/icp.h"
#include "registration_test_util.h"

namespace conform {
namespace {

using test::kDeg;

// Angle between two lines' directions, deg (sign ignored).
double line_angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, std::abs(a.normalized().dot(b.normalized())))) / kDeg;
}

// Distance of p from the line through o along d.
double distance_to_line(const Eigen::Vector3d& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = d.normalized();
  return ((p - o) - (p - o).dot(u) * u).norm();
}

std::vector<const DegenerateDirection*> of_kind(const DegeneracyReport& r, MotionKind kind) {
  std::vector<const DegenerateDirection*> out;
  for (const DegenerateDirection& d : r.directions) {
    if (d.kind == kind) out.push_back(&d);
  }
  return out;
}

TEST(Degeneracy, PlaneSlidesAndTurnsInItself) {
  std::vector<Eigen::Vector3d> q, n;
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 20; ++j) {
      q.emplace_back(5.0 * i, 5.0 * j, 10.0);
      n.emplace_back(0.0, 0.0, 1.0);
    }
  }
  const DegeneracyReport r = analyze_degeneracy(plane_normal_matrix(q, n), 1e-3);
  ASSERT_EQ(r.eigenvalues.size(), 6);
  EXPECT_NEAR(r.eigenvalues(5), 1.0, 1e-12);  // the translation along the normal; the rotations about x and y less
  const auto translations = of_kind(r, MotionKind::kTranslation);
  const auto rotations = of_kind(r, MotionKind::kRotation);
  ASSERT_EQ(translations.size(), 2u);
  ASSERT_EQ(rotations.size(), 1u);
  for (const auto* t : translations) EXPECT_NEAR(t->direction.z(), 0.0, 1e-12);
  EXPECT_LT(line_angle_deg(rotations[0]->direction, Eigen::Vector3d::UnitZ()), 1e-9);
}

TEST(Degeneracy, SphereTurnsAboutItsCentre) {
  std::vector<Eigen::Vector3d> q, n;
  const Eigen::Vector3d centre(30.0, -20.0, 5.0);
  Random random(1);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d u = test::random_direction(random);
    q.push_back(centre + 50.0 * u);
    n.push_back(u);
  }
  const DegeneracyReport r = analyze_degeneracy(plane_normal_matrix(q, n), 1e-3);
  ASSERT_EQ(of_kind(r, MotionKind::kRotation).size(), 3u);
  for (const DegenerateDirection& d : r.directions) {
    EXPECT_LT(distance_to_line(centre, d.point, d.direction), 1e-9);
    EXPECT_NEAR(d.pitch_mm_per_rad, 0.0, 1e-9);
  }
  // Translations alone: one eigenvalue 1/3 each.
  FreeDof translations_only;
  translations_only.rx = translations_only.ry = translations_only.rz = false;
  const DegeneracyReport t = analyze_degeneracy(plane_normal_matrix(q, n), 1e-3, translations_only);
  ASSERT_EQ(t.eigenvalues.size(), 3);
  EXPECT_NEAR(t.eigenvalues.sum(), 1.0, 1e-12);
  EXPECT_FALSE(t.degenerate());
}

// A tube patch (60 degrees of a 150 mm radius tube, 200 mm long, axis along world (1, 1, 0.5) through
// (400, -100, 50)) registered to a differently meshed, noisy copy of itself.
TEST(Degeneracy, TubePatchIsDegenerateAlongAndAboutItsAxisAndTheBoxIsNot) {
  TubeOptions tube;
  tube.radius_mm = 150.0;
  tube.length_mm = 200.0;
  tube.arc_rad = M_PI / 3.0;
  tube.edge_mm = 4.0;
  const Eigen::Vector3d axis_point(400.0, -100.0, 50.0), axis(1.0, 1.0, 0.5);
  tube.T_world_tube = tube_frame(axis_point, axis, default_azimuth_reference(axis));
  const IcpReference tube_ref(generate_tube(tube).mesh);
  tube.edge_mm = 3.0;
  tube.noise_mm = 0.02;
  tube.seed = 4;
  const std::vector<Eigen::Vector3d> tube_scan = generate_tube(tube).mesh.vertices;

  PartOptions part;
  part.edge_mm = 4.0;
  const IcpReference box_ref(box_part(part));
  part.edge_mm = 3.0;
  part.noise_mm = 0.02;
  part.seed = 4;
  const std::vector<Eigen::Vector3d> box_scan = box_part(part).vertices;

  for (IcpMethod method : {IcpMethod::kPointToPoint, IcpMethod::kPointToPlane, IcpMethod::kPointToSurface}) {
    SCOPED_TRACE(to_string(method));
    IcpOptions options;
    options.method = method;
    const IcpResult t = icp(tube_scan, tube_ref, Eigen::Isometry3d::Identity(), options);
    const IcpResult b = icp(box_scan, box_ref, Eigen::Isometry3d::Identity(), options);
    const auto fmt = [](const Eigen::VectorXd& e) {
      std::string s;
      for (Eigen::Index i = 0; i < e.size(); ++i) s += " " + std::to_string(e(i));
      return s;
    };
    std::printf("  %-16s tube eigenvalues%s\n  %-16s box  eigenvalues%s\n", to_string(method),
                fmt(t.degeneracy.eigenvalues).c_str(), "", fmt(b.degeneracy.eigenvalues).c_str());
    EXPECT_TRUE(t.converged);
    EXPECT_TRUE(b.converged);
    EXPECT_FALSE(b.degeneracy.degenerate());
    EXPECT_GT(b.degeneracy.relative_smallest(), 1e-2);

    ASSERT_EQ(t.degeneracy.directions.size(), 2u);
    const auto translations = of_kind(t.degeneracy, MotionKind::kTranslation);
    const auto rotations = of_kind(t.degeneracy, MotionKind::kRotation);
    ASSERT_EQ(translations.size(), 1u);
    ASSERT_EQ(rotations.size(), 1u);
    EXPECT_LT(line_angle_deg(translations[0]->direction, axis), 0.5);
    EXPECT_LT(line_angle_deg(rotations[0]->direction, axis), 0.5);
    EXPECT_LT(distance_to_line(rotations[0]->point, axis_point, axis), 1.0);  // the axis, within 1 mm
    EXPECT_LT(t.degeneracy.relative_smallest(), 1e-4);
    // The frozen directions kept their start (the identity), the others were fitted (to the truth, the identity).
    // Point-to-point is biased by the reference's 4 mm spacing, most across the patch, which the plane does not
    // constrain much either (the third eigenvalue).
    const bool p2p = method == IcpMethod::kPointToPoint;
    EXPECT_LT(t.T_ref_scan.translation().norm(), p2p ? 2.0 : 0.05);
    EXPECT_LT(test::rotation_error_deg(t.T_ref_scan, Eigen::Isometry3d::Identity()), p2p ? 0.5 : 0.01);
  }
}

}  // namespace
}  // namespace conform
