// Tool frames (robot/tool_frames.h) and the jobs' path files read as frames (robot/job_paths.h): against
// closed forms of lines, circles and the saddle seam, degenerate cases, and bad input.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/csv.h"
#include "conform/core/error.h"
#include "conform/pipelines/saddle/saddle.h"
#include "conform/robot/job_paths.h"
#include "conform/toolpath/saddle/saddle.h"
#include "conform/robot/tool_frames.h"

namespace conform {
namespace {

// A right-handed orthonormal frame with the given z.
void expect_frame(const ToolFrame& f, const Eigen::Vector3d& z, double tol) {
  const Eigen::Matrix3d& r = f.rotation;
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
  EXPECT_LT((r.col(2) - z.normalized()).norm(), tol);
}

// A table as read_csv would give it, from text (no file).
CsvTable table(const std::string& text) { return parse_csv(text, "test.csv"); }

ToolPathPoints line_points(std::size_t n, const Eigen::Vector3d& step, const Eigen::Vector3d& axis) {
  ToolPathPoints p;
  for (std::size_t i = 0; i < n; ++i) {
    p.positions.push_back(static_cast<double>(i) * step);
    p.tool_axes.push_back(axis);
  }
  return p;
}

TEST(ToolFrames, StraightLineTravelIsXAndYCompletesTheFrame) {
  // Travel along (1, 1, 0), tool straight down (-z of the base), axis given at length 3: z = (0,0,-1),
  // x = (1,1,0)/sqrt2, y = z x x = (1,-1,0)/sqrt2.
  const auto frames = build_tool_frames(line_points(5, {1, 1, 0}, {0, 0, -3}), {});
  ASSERT_EQ(frames.size(), 5u);
  for (const ToolFrame& f : frames) {
    expect_frame(f, {0, 0, -1}, 1e-15);
    EXPECT_LT((f.rotation.col(0) - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 1e-15);
    EXPECT_LT((f.rotation.col(1) - Eigen::Vector3d(1, -1, 0).normalized()).norm(), 1e-15);
  }
}

TEST(ToolFrames, TangentIsProjectedOffATiltedToolAxis) {
  // Travel along x with the tool tilted 30 deg in the xz plane: x = travel projected off z, exactly.
  const Eigen::Vector3d z(std::sin(kPi / 6), 0, -std::cos(kPi / 6));
  const auto frames = build_tool_frames(line_points(3, {2, 0, 0}, z), {});
  const Eigen::Vector3d expected = (Eigen::Vector3d::UnitX() - z.x() * z).normalized();
  for (const ToolFrame& f : frames) EXPECT_LT((f.rotation.col(0) - expected).norm(), 1e-15);
}

TEST(ToolFrames, ClosedCircleTangentWrapsRound) {
  // 36 points on a circle of radius 100 about z, tool pointing down: x is the exact tangent (-sin, cos, 0) at every
  // point, the first and last too (central differences of equal steps on a circle are exact in direction).
  ToolPathPoints p;
  for (int i = 0; i < 36; ++i) {
    const double a = 2 * kPi * i / 36;
    p.positions.emplace_back(100 * std::cos(a), 100 * std::sin(a), 0);
    p.tool_axes.emplace_back(0, 0, -1);
  }
  p.closed = true;
  const auto frames = build_tool_frames(p, {});
  for (int i = 0; i < 36; ++i) {
    const double a = 2 * kPi * i / 36;
    EXPECT_LT((frames[i].rotation.col(0) - Eigen::Vector3d(-std::sin(a), std::cos(a), 0)).norm(), 1e-12) << i;
  }
  ToolFrameFigures fig;
  ToolPath path;
  path.segments.push_back({"c", frames});
  measure_orientation_steps(path, &fig);
  EXPECT_NEAR(fig.max_orientation_step_rad, 2 * kPi / 36, 1e-12);
}

TEST(ToolFrames, TangentAlongTheToolAxisKeepsTheNeighboursX) {
  // A path along x, then a plunge straight down the tool axis, then along y: the plunge frames keep x from before.
  ToolPathPoints p;
  const std::vector<Eigen::Vector3d> pts = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 0, -1}, {2, 0, -2}};
  for (const auto& q : pts) {
    p.positions.push_back(q);
    p.tool_axes.emplace_back(0, 0, -1);
  }
  ToolFrameFigures fig;
  const auto frames = build_tool_frames(p, {}, &fig);
  EXPECT_EQ(fig.parallel_tangents, 2u);  // the plunge; the corner's tangent has an x part
  for (const auto& f : frames) EXPECT_LT((f.rotation.col(0) - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  for (const auto& f : frames) expect_frame(f, {0, 0, -1}, 1e-15);
}

TEST(ToolFrames, AllTangentsAlongTheAxisTakeTheLeastAlignedBaseAxis) {
  const auto frames = build_tool_frames(line_points(4, {0, 0, 1}, {0, 0, 1}), {});
  for (const auto& f : frames) {
    expect_frame(f, {0, 0, 1}, 1e-15);
    EXPECT_LT((f.rotation.col(0) - Eigen::Vector3d::UnitX()).norm(), 1e-15);
  }
}

TEST(ToolFrames, RepeatedPointsAndOnePointPaths) {
  ToolPathPoints p = line_points(4, {1, 0, 0}, {0, 0, -1});
  p.positions.insert(p.positions.begin() + 2, p.positions[2]);  // a repeat
  p.tool_axes.push_back({0, 0, -1});
  ToolFrameFigures fig;
  const auto frames = build_tool_frames(p, {}, &fig);
  EXPECT_EQ(fig.repeated_points, 1u);
  for (const auto& f : frames) EXPECT_LT((f.rotation.col(0) - Eigen::Vector3d::UnitX()).norm(), 1e-15);

  ToolPathPoints one;
  one.positions = {{5, 5, 5}};
  one.tool_axes = {{1, 0, 0}};
  EXPECT_LT((build_tool_frames(one, {})[0].rotation.col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  one.hints = {{0, 1, 1}};  // travel hint: its part off z
  EXPECT_LT((build_tool_frames(one, {})[0].rotation.col(0) - Eigen::Vector3d(0, 1, 1).normalized()).norm(), 1e-15);
}

TEST(ToolFrames, RollConeTurnsXTowardsThePreferredDirection) {
  // Travel along y, preferred x along +x, cone 30 deg: x is turned to 30 deg from +x towards +y.
  ToolFrameOptions o;
  o.roll_cone_rad = kPi / 6;
  ToolFrameFigures fig;
  const auto frames = build_tool_frames(line_points(3, {0, 1, 0}, {0, 0, -1}), o, &fig);
  EXPECT_EQ(fig.roll_limited, 3u);
  // z = -Z: a positive turn about z goes from +x towards -y.
  for (const auto& f : frames) {
    expect_frame(f, {0, 0, -1}, 1e-15);
    EXPECT_NEAR(std::acos(f.rotation.col(0).x()), kPi / 6, 1e-12);
    EXPECT_GT(f.rotation.col(0).y(), 0.0);
  }
}

TEST(ToolFrames, BadInputIsRefused) {
  ToolPathPoints p = line_points(3, {1, 0, 0}, {0, 0, -1});
  p.tool_axes[1] = Eigen::Vector3d::Zero();
  EXPECT_THROW(build_tool_frames(p, {}), Error);
  p.tool_axes[1] = {0, 0, -1};
  p.positions[2].x() = std::nan("");
  EXPECT_THROW(build_tool_frames(p, {}), Error);
  ToolFrameOptions o;
  o.roll_cone_rad = -1;
  EXPECT_THROW(build_tool_frames(line_points(3, {1, 0, 0}, {0, 0, -1}), o), Error);
}

TEST(ToolFrames, RotationAngleIsAccurateNearZeroAndPi) {
  for (double a : {1e-9, 1e-3, 1.0, kPi - 1e-7, kPi}) {
    const Eigen::Matrix3d r = Eigen::AngleAxisd(a, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    EXPECT_NEAR(rotation_angle_between(Eigen::Matrix3d::Identity(), r), a, 1e-12) << a;
  }
}

// Saddle, the paper's T joint (R 600, r 150, phi 45 deg), 1 deg steps, through the job's own CSV: where the surfaces
// meet at a right angle (theta 0 and pi, beta = pi/2) the torch bisects them, z = -(n_p + n_l)/sqrt 2 with the
// normals of the closed forms (docs/saddle.md); everywhere x is the seam's tangent dP/dtheta = (y, -x, z'(theta))
// (Eq. 1-3, 7) projected off z, to the central difference's error.
TEST(JobPaths, SaddleFramesAgainstTheSeamsClosedForms) {
  SaddleJobOptions o;
  o.saddle.step_rad = kPi / 180;
  const SaddleJobResult job = run_saddle(o);
  ToolFrameFigures fig;
  const ToolPath path = tool_path_from_csv(table(saddle_csv(job.saddle)), {}, &fig);
  EXPECT_EQ(path.job, "saddle");
  ASSERT_EQ(path.segments.size(), 1u);
  const auto& frames = path.segments[0].frames;
  ASSERT_EQ(frames.size(), job.saddle.points.size());
  ASSERT_GE(frames.size(), 361u);
  const double R = 600, r = 150;
  double worst_x = 0.0, worst_z = 0.0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const double th = job.saddle.points[i].theta_rad;
    const double x = r * std::sin(th), y = r * std::cos(th), z = std::sqrt(R * R - x * x);
    EXPECT_LT((frames[i].position - Eigen::Vector3d(x, y, z)).norm(), 1e-8);
    const Eigen::Vector3d tangent(y, -x, -x * r * std::cos(th) / z);  // z' = -x x' / z
    const Eigen::Vector3d zt = frames[i].rotation.col(2);
    const Eigen::Vector3d expected_x = (tangent - tangent.dot(zt) * zt).normalized();
    EXPECT_LT((frames[i].rotation.col(0) - expected_x).norm(), 5e-5) << i;
    worst_x = std::max(worst_x, (frames[i].rotation.col(0) - expected_x).norm());
    if (i == 0 || i == 180) {
      const Eigen::Vector3d n_p(std::sin(th), std::cos(th), 0);
      const Eigen::Vector3d n_l(x, 0, z);  // the cylinder's outward normal, (y_L, x_L cos p, x_L sin p)/R at p = 90
      EXPECT_LT((zt + (n_p + n_l.normalized()).normalized()).norm(), 1e-11) << i;
      worst_z = std::max(worst_z, (zt + (n_p + n_l.normalized()).normalized()).norm());
    }
  }
  std::printf("[ measured ] saddle 1 deg steps: x off the closed-form tangent by %.2e, z off the bisector by %.2e\n",
              worst_x, worst_z);
  EXPECT_LT(fig.max_orientation_step_rad, 2.0 * kPi / 180);
}

TEST(JobPaths, EachJobsColumnsAndSigns) {
  // sicp: z = -n.
  ToolPath p = tool_path_from_csv(table("x_mm,y_mm,z_mm,nx,ny,nz\n0,0,0,0,0,1\n1,0,0,0,0,1\n"), {});
  EXPECT_EQ(p.job, "sicp");
  expect_frame(p.segments[0].frames[0], {0, 0, -1}, 1e-15);
  // tube-joint cut/weld: z = +d, closed (the first frame repeated at the end).
  p = tool_path_from_csv(table("phi_rad,x_mm,y_mm,z_mm,dx,dy,dz,alpha_rad,psi_rad\n0,1,0,0,0,1,0,0,0\n"
                               "1,0,1,0,0,1,0,0,0\n2,-1,0,0,0,1,0,0,0\n"),
                         {});
  EXPECT_EQ(p.job, "tube-joint");
  ASSERT_EQ(p.segments[0].frames.size(), 4u);
  expect_frame(p.segments[0].frames[3], {0, 1, 0}, 1e-15);
  EXPECT_EQ(p.segments[0].frames[3].position, p.segments[0].frames[0].position);
  // profile: z = -n, one segment per id, centres (i = -1) left out, d the travel of a one-point feature.
  p = tool_path_from_csv(table("id,i,tx_mm,ty_mm,x_mm,y_mm,z_mm,nx,ny,nz,dx,dy,dz\nH1,-1,0,0,5,5,0,0,0,1,1,0,0\n"
                               "H1,0,0,0,6,5,0,0,0,1,0,1,0\nH1,1,0,0,5,6,0,0,0,1,-1,0,0\n"
                               "P1,0,0,0,9,9,0,0,0,1,0,1,0\n"),
                         {});
  EXPECT_EQ(p.job, "profile");
  ASSERT_EQ(p.segments.size(), 2u);
  EXPECT_EQ(p.segments[0].frames.size(), 2u);
  EXPECT_LT((p.segments[1].frames[0].rotation.col(0) - Eigen::Vector3d::UnitY()).norm(), 1e-15);
  expect_frame(p.segments[1].frames[0], {0, 0, -1}, 1e-15);
  // weld-layers: z = -n, one segment per (layer, path).
  p = tool_path_from_csv(table("layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz\n1,1,0,0,0,0,0,0,1\n1,1,1,1,0,0,0,0,1\n"
                               "1,2,0,0,3,0,0,0,1\n2,1,0,0,0,1,0,0,1\n"),
                         {});
  EXPECT_EQ(p.job, "weld-layers");
  EXPECT_EQ(p.segments.size(), 3u);
  EXPECT_EQ(p.segments[2].name, "layer 2 path 1");
}

TEST(JobPaths, FrameColumnsAreTakenAsGiven) {
  // 90 deg about x: z = (0, -1, 0); the approach row is left out, segments split by their column.
  const double h = std::sqrt(0.5);
  const std::string q = std::to_string(h);
  const ToolPath p = tool_path_from_csv(
      table("i,segment,kind,x_mm,y_mm,z_mm,qw,qx,qy,qz\n0,0,approach,0,0,50,1,0,0,0\n1,0,path,0,0,0," + q + "," + q +
            ",0,0\n2,0,path,1,0,0,1,0,0,0\n3,1,path,5,0,0,1,0,0,0\n"),
      {});
  EXPECT_EQ(p.job, "frames");
  ASSERT_EQ(p.segments.size(), 2u);
  ASSERT_EQ(p.segments[0].frames.size(), 2u);
  expect_frame(p.segments[0].frames[0], {0, -1, 0}, 1e-6);
  EXPECT_LT((p.segments[1].frames[0].rotation - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_THROW(tool_path_from_csv(table("x_mm,y_mm,z_mm,qw,qx,qy,qz\n0,0,0,2,0,0,0\n"), {}), Error);
}

// A column the job does not use still holds numbers (docs/export.md: exit 2), and a jump far beyond the path's own
// step is a broken row: 15 m between 8 mm steps refused, naming the segment and the points; allowed with ratio 0.
TEST(JobPaths, UnusedColumnsAreNumbersAndJumpsAreRefused) {
  const auto message = [](const std::string& text, double ratio) {
    ToolFrameOptions options;
    options.max_jump_ratio = ratio;
    try {
      tool_path_from_csv(table(text), options);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string header = "x_mm,y_mm,z_mm,nx,ny,nz,extra\n";
  EXPECT_NE(message(header + "0,0,0,0,0,1,abc\n8,0,0,0,0,1,1\n", 50).find("test.csv:2: column 'extra'"),
            std::string::npos);
  EXPECT_NE(message(header + "0,0,0,0,0,1,inf\n8,0,0,0,0,1,1\n", 50).find("column 'extra'"), std::string::npos);
  EXPECT_NE(message(header + "0,0,0,0,0,1,1e300\n8,0,0,0,0,1,1\n", 50).find("beyond"), std::string::npos);
  std::string jump = header;
  for (int i = 0; i < 10; ++i) jump += std::to_string(8 * i) + ",0,0,0,0,1,0\n";
  jump += "15072,0,0,0,0,1,0\n";
  const std::string why = message(jump, 50);
  EXPECT_NE(why.find("a jump of 15000 mm between points 10 and 11"), std::string::npos) << why;
  EXPECT_EQ(message(jump, 0), "no error");
  // 484 mm after two 8 mm steps: beyond 50 times; 384 mm is not.
  EXPECT_NE(message(header + "0,0,0,0,0,1,0\n8,0,0,0,0,1,0\n16,0,0,0,0,1,0\n500,0,0,0,0,1,0\n", 50).find("jump"),
            std::string::npos);
  EXPECT_EQ(message(header + "0,0,0,0,0,1,0\n8,0,0,0,0,1,0\n16,0,0,0,0,1,0\n400,0,0,0,0,1,0\n", 50), "no error");
}

TEST(JobPaths, BadFilesAreRefusedNamingTheProblem) {
  auto message = [](const std::string& text) {
    try {
      tool_path_from_csv(table(text), {});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("x_mm,y_mm,z_mm\n0,0,0\n").find("not a path file"), std::string::npos);
  EXPECT_NE(message("x_mm,y_mm,z_mm,nx,ny,nz\n0,0,0,0,0,nan\n").find("test.csv:2"), std::string::npos);
  EXPECT_NE(message("x_mm,y_mm,z_mm,nx,ny,nz\n0,0,0,0,0,2\n").find("not a unit vector"), std::string::npos);
  EXPECT_NE(message("x_mm,y_mm,z_mm,nx,ny,nz\n").find("no rows"), std::string::npos);
  EXPECT_NE(
      message("phi_rad,x_mm,y_mm,z_mm,tx,ty,tz,nsx,nsy,nsz,nlx,nly,nlz\n0,0,0,0,1,0,0,1,0,0,0,0,1\n").find("--out-cut"),
      std::string::npos);
  EXPECT_NE(message("layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz\n1,1,0,0,0,0,0,0,1\n1,2,0,0,0,0,0,0,1\n1,1,1,0,0,0,0,0,1\n")
                .find("comes back"),
            std::string::npos);
}

}  // namespace
}  // namespace conform
