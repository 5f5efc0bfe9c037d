// Tool directions against analytic ground truth: undeformed cylinders (generate_tube_joint with noise only), where
// the stub's inner normal at p is radial about z_S and the leg's radial about z_L. The stub normal, the leg normal,
// the seam tangent (Eq. 3), the dihedral angle between the surfaces and the cutting and welding directions (Eq. 9-11
// on the true frames) at every path point are compared with the truth at that point, and the point with the true seam.
// Each joint either meets the bars (directions within 2 deg, the path within 1 mm of the true seam) with ok, or is
// refused: a wrong answer with ok fails the test, and so does a refusal of a plan that meets the bars.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "tube_joint_fixture.h"

#include "conform/core/constants.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

struct DirectionErrors {
  double stub_normal_deg = 0.0, leg_normal_deg = 0.0, tangent_deg = 0.0, dihedral_deg = 0.0, cut_deg = 0.0;
  double weld_deg = 0.0;
  double path_max_mm = 0.0, path_rms_mm = 0.0;
  double worst_deg() const {
    return std::max({stub_normal_deg, leg_normal_deg, tangent_deg, dihedral_deg, cut_deg, weld_deg});
  }
};

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) / kDeg;
}

DirectionErrors measure(const TubeJointScans& scans, const TubeJointOptions& o, const TubeJointSolution& s) {
  DirectionErrors e;
  const Eigen::Isometry3d T_L_S = o.T_L_S;
  double sum = 0.0;
  // The cutting and welding directions the true frames give (Eq. 9-11, the solve's default tool options).
  std::vector<PathFrame> truth;
  for (const PathFrame& f : s.frames) {
    const Eigen::Vector3d q = T_L_S * f.point;
    truth.push_back(path_frame(f.phi_rad, f.point, Eigen::Vector3d(f.point.x(), f.point.y(), 0.0).normalized(),
                               (T_L_S.linear().transpose() * Eigen::Vector3d(q.x(), q.y(), 0.0)).normalized()));
  }
  if (!s.frames.empty()) {
    const ToolPaths tools = tool_paths(truth, TubeJointSolveOptions{}.tools);
    for (std::size_t i = 0; i < tools.cut.size(); ++i) {
      e.cut_deg = std::max(e.cut_deg, angle_deg(s.tools.cut[i].direction, tools.cut[i].direction));
      e.weld_deg = std::max(e.weld_deg, angle_deg(s.tools.weld[i].direction, tools.weld[i].direction));
    }
  }
  for (const PathFrame& f : s.frames) {
    const Eigen::Vector3d n_s(f.point.x(), f.point.y(), 0.0);
    const Eigen::Vector3d q = T_L_S * f.point;
    const Eigen::Vector3d n_l = T_L_S.linear().transpose() * Eigen::Vector3d(q.x(), q.y(), 0.0);
    const Eigen::Vector3d t = n_s.normalized().cross(n_l.normalized());
    e.stub_normal_deg = std::max(e.stub_normal_deg, angle_deg(f.stub_normal, n_s));
    e.leg_normal_deg = std::max(e.leg_normal_deg, angle_deg(f.leg_normal, n_l));
    e.tangent_deg = std::max(e.tangent_deg, angle_deg(f.tangent, t));
    e.dihedral_deg = std::max(e.dihedral_deg, std::abs(angle_deg(f.stub_normal, f.leg_normal) - angle_deg(n_s, n_l)));
    const double d = distance_to_truth(scans.truth, f.point);
    e.path_max_mm = std::max(e.path_max_mm, d);
    sum += d * d;
  }
  e.path_rms_mm = s.frames.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(s.frames.size()));
  return e;
}

struct Joint {
  const char* name;
  double pitch_deg, offset_mm, leg_radius_mm, stub_radius_mm, edge_mm, noise_mm;
};

void run(const Joint& j, const TubeJointSolveOptions& solve_options, int must_pass) {
  int passed = 0;
  for (unsigned seed = 0; seed < 2; ++seed) {
    test::JointCase c;
    c.pitch_deg = j.pitch_deg, c.offset_mm = j.offset_mm, c.edge_mm = j.edge_mm;
    c.leg_radius_mm = j.leg_radius_mm, c.stub_radius_mm = j.stub_radius_mm;
    TubeJointOptions o = test::joint_options(c);
    o.leg.noise_mm = o.stub.noise_mm = j.noise_mm;
    o.leg.seed = 300 + 2 * seed, o.stub.seed = 301 + 2 * seed;
    const TubeJointScans scans = generate_tube_joint(o);
    const TubeJointSolution s = solve_tube_joint(scans.leg_L, scans.stub_S, o.T_L_S.inverse(), solve_options);
    const DirectionErrors e = measure(scans, o, s);
    double sigma = 0.0, sigma_n = 0.0;
    for (const PathFrame& f : s.frames) {
      sigma = std::max(sigma, f.tangent_sigma_deg);
      sigma_n = std::max({sigma_n, f.stub_normal_sigma_deg, f.leg_normal_sigma_deg});
    }
    std::printf("  sigma: tangent max %.3f deg, normals max %.3f deg\n", sigma, sigma_n);
    std::printf(
        "%s seed %u: ok %d, stub n %.2f, leg n %.2f, tangent %.2f, dihedral %.2f, cut %.2f, weld %.2f deg; "
        "path max %.3f rms %.3f mm; %s\n",
        j.name, seed, int(s.ok), e.stub_normal_deg, e.leg_normal_deg, e.tangent_deg, e.dihedral_deg, e.cut_deg,
        e.weld_deg, e.path_max_mm, e.path_rms_mm, s.ok ? "" : s.termination.c_str());
    const bool meets = !s.frames.empty() && e.worst_deg() <= 2.0 && e.path_max_mm <= 1.0;
    if (s.ok) {
      EXPECT_TRUE(meets) << j.name << " seed " << seed << ": ok, but directions off by " << e.worst_deg()
                         << " deg, path " << e.path_max_mm << " mm";
      passed += meets;
    } else {
      EXPECT_FALSE(meets) << j.name << " seed " << seed << ": refused a right plan: " << s.termination;
    }
  }
  EXPECT_GE(passed, must_pass) << j.name;
}

// A fine noisy mesh: 1.5 mm edges, 0.3 mm noise (the default k = 40 normals were 4-5 deg off).
TEST(TubeJointDirectionsMatrix, FineNoisyMesh) {
  run({"pitch 45, 1.5 mm, 0.3 mm noise", 45.0, 0.0, 300.0, 125.0, 1.5, 0.3}, {}, 2);
}

// Near the offset limit: offset + r = R - 3 mm, the surfaces cross at a grazing angle at the sides (the tangent and
// dihedral were 15-22 deg off with exit 0).
TEST(TubeJointDirectionsMatrix, ThreeMillimetresFromTangent) {
  run({"pitch 90, offset R - r - 3, 2 mm, 0.2 mm noise", 90.0, 300.0 - 125.0 - 3.0, 300.0, 125.0, 2.0, 0.2}, {}, 0);
}

// Half a millimetre from tangent on a 3 mm mesh with 0.5 mm noise: the tangent cannot be determined at the sides.
TEST(TubeJointDirectionsMatrix, HalfAMillimetreFromTangentVeryNoisy) {
  run({"pitch 90, offset R - r - 0.5, 3 mm, 0.5 mm noise", 90.0, 300.0 - 125.0 - 0.5, 300.0, 125.0, 3.0, 0.5}, {}, 0);
}

// The crossing at ~11 deg (offset 0.94 (R - r)) with 0.2 mm noise on 2 mm meshes: the path was up to 0.93 mm off.
TEST(TubeJointDirectionsMatrix, GrazingCrossingPath) {
  run({"pitch 45, offset 0.94 (R - r), 2 mm, 0.2 mm noise", 45.0, 0.94 * 175.0, 300.0, 125.0, 2.0, 0.2}, {}, 2);
}

}  // namespace
}  // namespace conform
