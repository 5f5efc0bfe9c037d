// generate_tube_joint: the ground truth lies on both exact deformed surfaces, the meshes are where the frames say,
// the same options give the same meshes, and bad options are named.

#include "conform/datasets/tube_joint.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/datasets/tube_surface.h"
#include "conform/pipelines/generate/generate_tube_joint.h"

namespace conform {
namespace {

TubeJointOptions options() {
  TubeJointSpec spec;
  spec.pitch_rad = 50.0 * kPi / 180.0;
  spec.offset_mm = 40.0;
  spec.protrusion_mm = automatic_protrusion(spec.pitch_rad, 300.0, 150.0, 40.0);
  TubeJointOptions o;
  o.T_L_S = T_L_S(spec);
  o.protrusion_mm = spec.protrusion_mm;
  o.leg.radius_mm = 300.0;
  o.leg.edge_mm = 8.0;
  o.leg.ovality_mm = 1.5;
  o.leg.seam_height_mm = 3.0;
  o.leg.seam_width_mm = 100.0;
  o.leg.bumps.push_back({0.1, 30.0, 2.0, 40.0});
  o.stub.radius_mm = 140.0;
  o.stub.edge_mm = 8.0;
  o.stub.ovality_mm = 0.7;
  o.stub.seam_height_mm = -2.0;
  o.stub.seam_azimuth_rad = 2.0;
  o.stub.bumps.push_back({1.0, 300.0, 1.5, 30.0});
  o.leg_margin_mm = 20.0;
  o.truth_points = 360;
  return o;
}

TEST(TubeJointGenerator, TruthLiesOnBothDeformedSurfaces) {
  const TubeJointOptions o = options();
  const TubeJointTruth truth = tube_joint_truth(o);
  ASSERT_EQ(truth.points.size(), 360u);
  for (std::size_t i = 0; i < truth.points.size(); ++i) {
    const Eigen::Vector3d& p = truth.points[i];
    // On the leg: bisection to 1e-10 mm along the stub wall.
    EXPECT_NEAR(leg_surface_distance(truth, o.T_L_S, p), 0.0, 1e-6) << i;
    // On the stub's inner wall at its azimuth: radius r(phi, z) in the stub's tube frame.
    const double phi = truth.phi_rad[i];
    EXPECT_NEAR(wrap_angle(std::atan2(p.y(), p.x()) - phi), 0.0, 1e-9);
    const double z_tube = p.z() - 0.5 * truth.stub.length_mm;
    EXPECT_NEAR(p.head<2>().norm(), tube_radius(truth.stub, phi, z_tube), 1e-9);
    EXPECT_NEAR(p.z(), truth.stub_z_mm[i], 1e-12);
  }
}

TEST(TubeJointGenerator, MeshesAreDeterministicAndPlacedInTheirFrames) {
  const TubeJointOptions o = options();
  const TubeJointScans a = generate_tube_joint(o);
  const TubeJointScans b = generate_tube_joint(o);
  EXPECT_EQ(a.leg_L.vertices, b.leg_L.vertices);
  EXPECT_EQ(a.stub_S.vertices, b.stub_S.vertices);
  // The stub spans z_S from its distal end (0) to its length; the leg's vertices are on its surface in L.
  double z_min = 1e300;
  double z_max = -1e300;
  for (const Eigen::Vector3d& v : a.stub_S.vertices) {
    z_min = std::min(z_min, v.z());
    z_max = std::max(z_max, v.z());
  }
  EXPECT_NEAR(z_min, 0.0, 1e-9);
  EXPECT_NEAR(z_max, a.truth.stub.length_mm, 1e-9);
  EXPECT_LT(a.truth.stub.length_mm, o.protrusion_mm);  // shortened to end inside the leg
  for (std::size_t i = 0; i < a.leg_L.vertices.size(); i += 97) {
    const Eigen::Vector3d& v = a.leg_L.vertices[i];
    EXPECT_NEAR(v.head<2>().norm(), tube_radius(a.truth.leg, std::atan2(v.y(), v.x()), v.z()), 1e-9);
  }
}

TEST(TubeJointGenerator, AStubThatMissesTheLegOrBadOptionsAreNamed) {
  TubeJointOptions o = options();
  o.protrusion_mm = 100.0;  // the distal end inside the leg
  EXPECT_THROW(tube_joint_truth(o), Error);
  o = options();
  o.stub.radius_mm = 400.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("leg radius"), std::string::npos) << why;
  o = options();
  o.truth_points = 3;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("truth points"), std::string::npos) << why;
  o = options();
  o.T_L_S = Eigen::Translation3d(0, 5000, 0) * o.T_L_S;  // the stub passes beside the leg (the analytic leg is endless)
  try {
    tube_joint_truth(o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("azimuth"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace conform
