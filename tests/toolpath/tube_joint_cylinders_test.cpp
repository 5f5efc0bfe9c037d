// Perfect cylinders, no noise: the computed path against the analytic intersection (toolpath/saddle/saddle_curve.h) for
// pitch 90, 45, 30 deg with and without offset; normals, tangent and tool directions against closed forms.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/toolpath/saddle/saddle_curve.h"
#include "tube_joint_fixture.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

struct Measured {
  double pipe_residual = 0.0;  // max distance of a path point from the stub cylinder
  double leg_residual = 0.0;   // ... from the leg cylinder
  double curve_mm = 0.0;       // max distance from the analytic curve (densely sampled)
  double normal_deg = 0.0;     // max angle of n_s or n_l from the analytic normal
};

SaddleCurve analytic_curve(const test::JointCase& c) {
  const TubeJointSpec spec = test::joint_spec(c);
  SaddleGeometry geometry;
  geometry.leg_radius_mm = c.leg_radius_mm;
  geometry.pipe_radius_mm = c.stub_radius_mm;
  geometry.pitch_rad = spec.pitch_rad;
  geometry.offset_mm = spec.offset_mm;
  return SaddleCurve(geometry);
}

TubeJointSolution solve_case(const test::JointCase& c, const TubeJointScans& scans, const ToolPathOptions& tools = {},
                             int k_refine = 40) {
  TubeJointSolveOptions solve;
  solve.geometry.k_refine = k_refine;
  solve.sampling.step_rad = 2.0 * kDeg;
  solve.tools = tools;
  const TubeJointSolution solution =
      solve_tube_joint(scans.leg_L, scans.stub_S, T_L_S(test::joint_spec(c)).inverse(), solve);
  EXPECT_TRUE(solution.ok) << solution.termination;
  return solution;
}

Measured measure(const test::JointCase& c, const TubeJointSolution& solution) {
  const SaddleCurve curve = analytic_curve(c);
  const Eigen::Isometry3d T_P_S = T_S_P(test::joint_spec(c)).inverse();
  std::vector<Eigen::Vector3d> dense;
  for (int k = 0; k < 20000; ++k) dense.push_back(T_P_S.inverse() * curve.point(2.0 * kPi * k / 20000));
  Measured m;
  for (const PathFrame& f : solution.frames) {
    double nearest = 1e300;
    for (std::size_t k = 0; k < dense.size(); ++k) {
      const Eigen::Vector3d& a = dense[k];
      const Eigen::Vector3d ab = dense[(k + 1) % dense.size()] - a;
      const double t = std::clamp((f.point - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      nearest = std::min(nearest, (f.point - a - t * ab).norm());
    }
    m.curve_mm = std::max(m.curve_mm, nearest);
    const Eigen::Vector3d p_P = T_P_S * f.point;
    m.pipe_residual = std::max(m.pipe_residual, std::abs(curve.pipe_residual(p_P)));
    m.leg_residual = std::max(m.leg_residual, std::abs(curve.leg_residual(p_P)));
    const Eigen::Vector3d n_s = T_P_S.linear().transpose() * curve.pipe_normal(f.phi_rad);
    const Eigen::Vector3d n_l = T_P_S.linear().transpose() * curve.leg_normal(f.phi_rad);
    const double a_s = std::acos(std::min(1.0, n_s.dot(f.stub_normal))) / kDeg;
    const double a_l = std::acos(std::min(1.0, n_l.dot(f.leg_normal))) / kDeg;
    m.normal_deg = std::max({m.normal_deg, a_s, a_l});
  }
  return m;
}

class CylinderJoint : public ::testing::TestWithParam<test::JointCase> {};

TEST_P(CylinderJoint, PathLiesOnBothCylindersWithinTheFacetSagittaAndNormalsWithinATenthOfADegree) {
  const test::JointCase c = GetParam();
  const TubeJointScans scans = generate_tube_joint(test::joint_options(c));
  const double stub_sagitta = test::facet_sagitta(scans.truth.stub);
  const double leg_sagitta = test::facet_sagitta(scans.truth.leg);
  const Measured m = measure(c, solve_case(c, scans, {}, 0));
  const Measured refined = measure(c, solve_case(c, scans, {}, 40));
  std::printf("pitch %g offset %g refined: stub %.5f leg %.5f curve %.5f mm normals %.4f deg\n", c.pitch_deg,
              c.offset_mm, refined.pipe_residual, refined.leg_residual, refined.curve_mm, refined.normal_deg);
  // Refined onto the local surface fits: on the cylinders to well below the sagitta (4th-order fit error).
  EXPECT_LE(refined.curve_mm, 0.1 * (stub_sagitta + leg_sagitta));
  EXPECT_LE(refined.normal_deg, 0.1);
  std::printf("pitch %g offset %g: stub %.4f (sagitta %.4f) leg %.4f (sagitta %.4f) curve %.4f mm normals %.4f deg\n",
              c.pitch_deg, c.offset_mm, m.pipe_residual, stub_sagitta, m.leg_residual, leg_sagitta, m.curve_mm,
              m.normal_deg);
  // The paper's path (the intersection polyline, resampled, not refined) lies on the facets of both meshes, so inside
  // each cylinder by at most that mesh's facet sagitta.
  EXPECT_LE(m.pipe_residual, stub_sagitta + 1e-9);
  EXPECT_LE(m.leg_residual, leg_sagitta + 1e-9);
  // Off the curve itself: a point within s1 of one surface and s2 of the other is within (s1 + s2) / sin(beta) of
  // their intersection line, beta the angle between the surfaces (smallest along the seam).
  const SaddleCurve curve = analytic_curve(c);
  double sin_beta = 1.0;
  for (int k = 0; k < 3600; ++k) sin_beta = std::min(sin_beta, std::sin(curve.dihedral(2.0 * kPi * k / 3600)));
  EXPECT_LE(m.curve_mm, (stub_sagitta + leg_sagitta) / sin_beta);
  // The quadric-corrected PCA normal on a noise-free cylinder: second-order exact, the rest is the facets.
  EXPECT_LE(m.normal_deg, 0.1);
}

INSTANTIATE_TEST_SUITE_P(PitchAndOffset, CylinderJoint,
                         ::testing::Values(test::JointCase{90.0, 0.0}, test::JointCase{90.0, 60.0},
                                           test::JointCase{45.0, 0.0}, test::JointCase{45.0, -60.0},
                                           test::JointCase{30.0, 0.0}, test::JointCase{30.0, 60.0}));

// The T joint, closed forms in S (stub radius r, leg radius R, a = r / R, b = sqrt(1 - a^2)):
//   toe  (phi 0):    n_s = (1, 0, 0),  n_l = (0, 0, -1),  t = (0, 1, 0),   t_l_out = (1, 0, 0)
//   side (pi/2):     n_s = (0, 1, 0),  n_l = (0, a, -b),  t = (-1, 0, 0),  t_l_out = (0, b, a)
//   heel (pi):       n_s = (-1, 0, 0), n_l = (0, 0, -1),  t = (0, -1, 0),  t_l_out = (-1, 0, 0)
//   side (3 pi/2):   n_s = (0, -1, 0), n_l = (0, -a, -b), t = (1, 0, 0),   t_l_out = (0, -b, a)
// d_c = cos(alpha_c) t_l_out + sin(alpha_c) n_l, d_w = -cos(alpha_w) t_l_out - sin(alpha_w) n_l.
TEST(CylinderJointDirections, TJointTangentCuttingAndWeldingDirectionsMatchTheClosedForms) {
  const test::JointCase c{90.0, 0.0};
  const TubeJointScans scans = generate_tube_joint(test::joint_options(c));
  ToolPathOptions tools;
  tools.groove_rad = {30.0 * kDeg, 45.0 * kDeg, 20.0 * kDeg, 45.0 * kDeg};
  tools.weld_angle_rad = 40.0 * kDeg;
  tools.cut_standoff_mm = 12.0;
  tools.weld_standoff_mm = 18.0;
  const TubeJointSolution solution = solve_case(c, scans, tools);
  ASSERT_EQ(solution.frames.size(), 180u);
  const double a = c.stub_radius_mm / c.leg_radius_mm;
  const double b = std::sqrt(1.0 - a * a);
  struct Quarter {
    std::size_t index;
    Eigen::Vector3d n_s, n_l, t, out;
    double groove_deg;
  };
  const Quarter quarters[] = {
      {0, {1, 0, 0}, {0, 0, -1}, {0, 1, 0}, {1, 0, 0}, 30.0},
      {45, {0, 1, 0}, {0, a, -b}, {-1, 0, 0}, {0, b, a}, 45.0},
      {90, {-1, 0, 0}, {0, 0, -1}, {0, -1, 0}, {-1, 0, 0}, 20.0},
      {135, {0, -1, 0}, {0, -a, -b}, {1, 0, 0}, {0, -b, a}, 45.0},
  };
  // 0.05 deg: the normals come out within 0.003 deg (above); the directions are built from them.
  const double tolerance = 0.05 * kDeg;
  const auto angle = [](const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
    return std::atan2(x.cross(y).norm(), x.dot(y));
  };
  for (const Quarter& q : quarters) {
    const PathFrame& f = solution.frames[q.index];
    SCOPED_TRACE(f.phi_rad / kDeg);
    EXPECT_LT(angle(f.stub_normal, q.n_s), tolerance);
    EXPECT_LT(angle(f.leg_normal, q.n_l), tolerance);
    EXPECT_LT(angle(f.tangent, q.t), tolerance);
    EXPECT_LT(angle(f.leg_out, q.out), tolerance);
    const double alpha = q.groove_deg * kDeg;
    const Eigen::Vector3d d_c = std::cos(alpha) * q.out + std::sin(alpha) * q.n_l;
    const Eigen::Vector3d d_w = -std::cos(40.0 * kDeg) * q.out - std::sin(40.0 * kDeg) * q.n_l;
    EXPECT_NEAR(solution.tools.groove_rad[q.index], alpha, 1e-12);
    EXPECT_LT(angle(solution.tools.cut[q.index].direction, d_c), tolerance);
    EXPECT_LT(angle(solution.tools.weld[q.index].direction, d_w), tolerance);
    // Eq. (9), (11): the standoffs along the directions, exactly.
    EXPECT_NEAR((f.point - solution.tools.cut[q.index].position).norm(), 12.0, 1e-9);
    EXPECT_NEAR((f.point - solution.tools.weld[q.index].position).norm(), 18.0, 1e-9);
    EXPECT_NEAR((f.point - solution.tools.cut[q.index].position).dot(solution.tools.cut[q.index].direction), 12.0,
                1e-9);
  }
}

// Any pitch and offset: the same equations applied to the analytic normals of saddle_curve.h.
TEST(CylinderJointDirections, PitchedOffsetJointDirectionsMatchTheAnalyticNormals) {
  const test::JointCase c{45.0, 60.0};
  const TubeJointScans scans = generate_tube_joint(test::joint_options(c));
  ToolPathOptions tools;
  // At the heel the dihedral angle is 45 deg (the pitch): the groove must stay below it (tool_safety.h).
  tools.groove_rad = {10.0 * kDeg, 35.0 * kDeg, 40.0 * kDeg, 35.0 * kDeg};
  tools.weld_angle_rad = 30.0 * kDeg;
  const TubeJointSolution solution = solve_case(c, scans, tools);
  const SaddleCurve curve = analytic_curve(c);
  const Eigen::Matrix3d R_S_P = T_S_P(test::joint_spec(c)).linear();
  for (const std::size_t i : {0u, 45u, 90u, 135u}) {
    const PathFrame& f = solution.frames[i];
    const Eigen::Vector3d n_s = R_S_P * curve.pipe_normal(f.phi_rad);
    const Eigen::Vector3d n_l = R_S_P * curve.leg_normal(f.phi_rad);
    const Eigen::Vector3d t = n_s.cross(n_l).normalized();
    const Eigen::Vector3d out = n_l.cross(t);
    const double alpha = tools.groove_rad[i / 45];
    const Eigen::Vector3d d_c = std::cos(alpha) * out + std::sin(alpha) * n_l;
    const Eigen::Vector3d d_w = -std::cos(30.0 * kDeg) * out - std::sin(30.0 * kDeg) * n_l;
    SCOPED_TRACE(i);
    EXPECT_GT(f.tangent.dot(t), std::cos(0.05 * kDeg));
    EXPECT_GT(solution.tools.cut[i].direction.dot(d_c), std::cos(0.05 * kDeg));
    EXPECT_GT(solution.tools.weld[i].direction.dot(d_w), std::cos(0.05 * kDeg));
    // The tangent runs along the analytic curve.
    EXPECT_GT(std::abs(f.tangent.dot((R_S_P * curve.derivative(f.phi_rad)).normalized())), std::cos(0.05 * kDeg));
  }
}

}  // namespace
}  // namespace conform
