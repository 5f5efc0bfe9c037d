// The tool safety checks on one hand-made seam point where the answer is known in closed form: a T joint's toe,
// stub wall along -z_S (psi = 90 deg), leg surface the plane z = z0 with the leg beyond it. A weld torch at alpha_w
// in the wall's wedge (alpha_c, psi) is inside the wall unless s_w sin(psi - alpha_w) > d_s.

#include "conform/toolpath/intersection/tool_safety.h"

#include <cmath>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"

namespace conform {
namespace {

constexpr double kDeg = kPi / 180.0;

struct Seam {
  std::vector<PathFrame> frames;
  TubeAxis leg_axis;
};

Seam toe() {
  Seam seam;
  const Eigen::Vector3d p(250.0, 0.0, 1000.0);
  // n_s outward from the stub axis, n_l outward from the leg (back up the stub): t = n_s x n_l = +y, t_l_out = +x.
  seam.frames.push_back(path_frame(0.0, p, Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitZ()));
  seam.leg_axis.point = Eigen::Vector3d(0.0, 0.0, 1000.0 + 600.0);  // R 600, the leg axis along x_S
  seam.leg_axis.direction = Eigen::Vector3d::UnitX();
  return seam;
}

ToolSafetyResult check(double groove_deg, double weld_deg, double weld_standoff, double wall) {
  const Seam seam = toe();
  ToolPathOptions tools;
  tools.groove_rad = {groove_deg * kDeg, groove_deg * kDeg, groove_deg * kDeg, groove_deg * kDeg};
  tools.weld_angle_rad = weld_deg * kDeg;
  tools.weld_standoff_mm = weld_standoff;
  ToolSafetyOptions options;
  options.stub_wall_mm = wall;
  const ToolPaths paths = tool_paths(seam.frames, tools);
  EXPECT_NEAR(paths.psi_rad[0], 90.0 * kDeg, 1e-12);
  return check_tool_safety(seam.frames, paths, seam.leg_axis, tools, options);
}

TEST(ToolSafety, AWeldTorchInTheGrooveIsClear) {
  const ToolSafetyResult r = check(30.0, 20.0, 15.0, 25.0);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(r.walls_checked);
}

TEST(ToolSafety, AWeldAngleAboveTheGrooveAngleIsInsideTheWallUnlessTheStandoffClearsIt) {
  // 15 sin(50 deg) = 11.5 mm < 25 mm: inside.
  const ToolSafetyResult inside = check(30.0, 40.0, 15.0, 25.0);
  EXPECT_FALSE(inside.ok);
  EXPECT_EQ(inside.weld_tip_in_stub.count, 1u);
  EXPECT_NE(inside.message.find("inside the stub wall"), std::string::npos) << inside.message;
  // 40 sin(50 deg) = 30.6 mm > 25 mm: beyond the outer surface; its approach line still crosses the wall.
  const ToolSafetyResult beyond = check(30.0, 40.0, 40.0, 25.0);
  EXPECT_EQ(beyond.weld_tip_in_stub.count, 0u);
  EXPECT_EQ(beyond.weld_line_in_material.count, 1u);
  // Without a wall thickness the wall is not checked.
  EXPECT_TRUE(check(30.0, 40.0, 15.0, 0.0).ok);
}

TEST(ToolSafety, TheCuttingTorchStandsInTheHollowAndAGrooveBeyondTheDihedralFails) {
  EXPECT_EQ(check(30.0, 20.0, 15.0, 25.0).cut_tip_in_stub.count, 0u);
  // Tilt the leg so that the dihedral angle at the point is 40 deg: a 45 deg groove cannot be cut.
  Seam seam = toe();
  const Eigen::Vector3d n_l(-std::sin(50.0 * kDeg), 0.0, -std::cos(50.0 * kDeg));
  seam.frames[0] = path_frame(0.0, seam.frames[0].point, Eigen::Vector3d::UnitX(), n_l);
  ToolPathOptions tools;
  tools.groove_rad = {45.0 * kDeg, 45.0 * kDeg, 45.0 * kDeg, 45.0 * kDeg};
  tools.weld_angle_rad = 10.0 * kDeg;
  const ToolPaths paths = tool_paths(seam.frames, tools);
  EXPECT_NEAR(paths.psi_rad[0], 40.0 * kDeg, 1e-9);
  const ToolSafetyResult r = check_tool_safety(seam.frames, paths, seam.leg_axis, tools, {});
  EXPECT_EQ(r.groove_beyond_wall.count, 1u);
  EXPECT_FALSE(r.ok);
}

TEST(ToolSafety, InvalidOptionsThrow) {
  const Seam seam = toe();
  const ToolPaths paths = tool_paths(seam.frames, {});
  ToolSafetyOptions options;
  options.stub_wall_mm = -1.0;
  EXPECT_THROW(check_tool_safety(seam.frames, paths, seam.leg_axis, {}, options), Error);
}

}  // namespace
}  // namespace conform
