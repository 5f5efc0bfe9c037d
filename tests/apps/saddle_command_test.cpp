// `conform saddle` end to end: the CSV it writes, its JSON, and exit code 2 with a message for bad input.

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult saddle(std::vector<std::string> args) {
  args.insert(args.begin(), "saddle");
  return test::run(CONFORM_EXE, args);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<double> fields(const std::string& row) {
  std::vector<double> out;
  std::istringstream in(row);
  for (std::string field; std::getline(in, field, ',');) out.push_back(std::stod(field));
  return out;
}

const std::vector<std::string> kPapersJoint = {"--R", "600", "--r", "150", "--start-pose-deg", "45"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

TEST(SaddleCommand, WritesThePapersTable1AsCsv) {
  test::TempDir dir;
  const auto r = saddle(with(kPapersJoint, {"--step-deg", "9", "--out", dir.file("table1.csv")}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("equal-angle"), std::string::npos) << r.out;
  const std::vector<std::string> rows = lines(test::read_bytes(dir.file("table1.csv")));
  ASSERT_EQ(rows.size(), 42u);
  EXPECT_EQ(rows[0], "i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm");
  // Row 11 of Table 1: theta 1.5708, x 150.0000, y 0.0000, z 580.9475, pose 1.0381.
  const std::vector<double> row11 = fields(rows[11]);
  ASSERT_EQ(row11.size(), 7u);
  EXPECT_EQ(row11[0], 10.0);
  EXPECT_NEAR(row11[1], 1.5708, 0.5e-4);
  EXPECT_NEAR(row11[2], 150.0000, 0.5e-4);
  EXPECT_NEAR(row11[3], 0.0000, 0.5e-4);
  EXPECT_NEAR(row11[4], 580.9475, 0.5e-4);
  EXPECT_NEAR(row11[5], 1.0381, 0.5e-4);
  EXPECT_EQ(dir.listing(), "table1.csv\n");
}

TEST(SaddleCommand, JsonHasTheFiguresAndNothingElseOnStdout) {
  const auto r = saddle(with(kPapersJoint, {"--speed", "500", "--period", "0.004", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);  // throws if anything else is on stdout
  for (const char* key : {"points", "step_mm_min", "step_mm_max", "speed_ripple_pct", "interpolation", "out"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["interpolation"], "variable-angle");
  EXPECT_GT(j["points"].get<int>(), 400);
  EXPECT_LT(j["speed_ripple_pct"].get<double>(), 0.1);
  EXPECT_NEAR(j["step_mm_min"].get<double>(), 2.0, 1e-3);
  EXPECT_NEAR(j["step_mm_max"].get<double>(), 2.0, 1e-3);
  EXPECT_TRUE(j["out"].is_null());
}

TEST(SaddleCommand, PitchedOffsetJointStepsByArcLength) {
  test::TempDir dir;
  const auto r = saddle(with(kPapersJoint, {"--pitch-deg", "45", "--offset", "100", "--speed", "500", "--period",
                                            "0.004", "--out", dir.file("p.csv"), "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["interpolation"], "arc-length");
  EXPECT_LE(j["max_cylinder_residual_mm"].get<double>(), 1e-9);
  EXPECT_LE(j["max_pipe_residual_mm"].get<double>(), 1e-9);
  EXPECT_EQ(j["out"], dir.file("p.csv"));
  EXPECT_EQ(lines(test::read_bytes(dir.file("p.csv"))).size(), j["points"].get<std::size_t>() + 1);
}

struct BadInput {
  std::vector<std::string> args;
  std::string message;
};

TEST(SaddleCommand, BadInputExitsTwoWithAMessageAndWritesNothing) {
  const std::vector<BadInput> cases = {
      {{"--R", "600", "--r", "600.5", "--start-pose-deg", "45", "--step-deg", "9"}, "must not be larger than the cyl"},
      {{"--R", "600", "--r", "900", "--start-pose-deg", "45", "--step-deg", "9"}, "must not be larger than the cyl"},
      {{"--R", "600", "--r", "0", "--start-pose-deg", "45", "--step-deg", "9"},
       "pipe radius r = 0 mm must be positive"},
      {{"--R", "-5", "--r", "150", "--start-pose-deg", "45", "--step-deg", "9"}, "radius R = -5 mm must be positive"},
      {with(kPapersJoint, {"--speed", "0", "--period", "0.004"}), "speed 0 mm/s must be a positive number"},
      {with(kPapersJoint, {"--speed", "-1", "--period", "0.004"}), "speed -1 mm/s must be a positive number"},
      {with(kPapersJoint, {"--speed", "1", "--period", "0"}), "period 0 s must be a positive number"},
      {with(kPapersJoint, {"--step-deg", "0"}), "angle step 0 deg is outside (0, 180) deg"},
      {with(kPapersJoint, {"--step-deg", "-9"}), "outside (0, 180) deg"},
      {with(kPapersJoint, {"--step-deg", "360"}), "outside (0, 180) deg"},
      {with(kPapersJoint, {"--pitch-deg", "0", "--step-deg", "9"}), "pitch 0 deg is outside [1, 90] deg"},
      {with(kPapersJoint, {"--pitch-deg", "1e-300", "--step-deg", "9"}), "is outside [1, 90] deg"},
      {with(kPapersJoint, {"--pitch-deg", "120", "--step-deg", "9"}), "pitch 120 deg is outside [1, 90] deg"},
      {{"--R", "600", "--r", "150", "--start-pose-deg", "1e308", "--step-deg", "9"}, "in (-180, 180] deg"},
      {{"--R", "600", "--r", "150", "--start-pose-deg", "-180", "--step-deg", "9"}, "in (-180, 180] deg"},
      {{"--R", "600", "--r", "150", "--start-pose-deg", "nan", "--step-deg", "9"}, "in (-180, 180] deg"},
      {with(kPapersJoint, {"--offset", "460", "--step-deg", "9"}), "offset 460 mm is too large"},
      {with(kPapersJoint, {"--speed", "1000", "--period", "1"}), "longer than the pipe radius"},
      {kPapersJoint, "give --step-deg"},
      {with(kPapersJoint, {"--speed", "1"}), "--period"},
      {with(kPapersJoint, {"--step-deg", "9", "--speed", "1", "--period", "1"}), "excludes"},
      {{"--r", "150", "--start-pose-deg", "45", "--step-deg", "9"}, "--R"},
  };
  for (const BadInput& bad : cases) {
    test::TempDir dir;
    const auto r = saddle(with(bad.args, {"--out", dir.file("out.csv")}));
    std::string joined;
    for (const std::string& a : bad.args) joined += a + " ";
    EXPECT_EQ(r.exit_code, 2) << joined << "\n" << r.err;
    EXPECT_NE(r.err.find(bad.message), std::string::npos) << joined << "\n" << r.err;
    EXPECT_TRUE(r.out.empty()) << joined << "\n" << r.out;
    EXPECT_EQ(dir.listing(), "") << joined;  // no output file, no temporary left behind
  }
}

TEST(SaddleCommand, UnwritableOutputExitsTwoNamingTheFile) {
  const auto r = saddle(with(kPapersJoint, {"--step-deg", "9", "--out", "/nonexistent-dir/x.csv"}));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent-dir/x.csv"), std::string::npos) << r.err;
}

// Issue 18: r = R (equal diameters) was refused. The path stops on both corners; the pose option by its new name.
TEST(SaddleCommand, EqualDiametersRunAndStopOnBothCorners) {
  const auto r = saddle(
      {"--R", "600", "--r", "600", "--right-angle-pose-deg", "45", "--speed", "250", "--period", "0.004", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["corner_steps"], 2);
  EXPECT_EQ(j["right_angle_pose_deg"], 45.0);
  EXPECT_EQ(j["converged"], true);
  EXPECT_LE(j["path_length_mm"].get<double>(), j["curve_length_mm"].get<double>());
}

TEST(SaddleCommand, HelpGivesUnitsAndDefaults) {
  const auto r = saddle({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* text :
       {"--R", "--r", "--pitch-deg", "--offset", "--right-angle-pose-deg", "--start-pose-deg", "--step-deg", "--speed",
        "--period", "--out", "--json", "mm/s", "--pitch-deg FLOAT=90", "--offset FLOAT=0"}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace conform
