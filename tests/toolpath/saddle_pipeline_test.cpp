// The `conform saddle` pipeline: its CSV, written whole or not at all, and its errors.

#include "conform/pipelines/saddle/saddle.h"

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "temp_dir.h"

namespace conform {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(SaddlePipeline, WritesThePapersTableAsCsv) {
  test::TempDir dir;
  SaddleJobOptions options;  // the paper's joint and Table 1's equal steps
  options.out_path = dir.file("saddle.csv");
  const SaddleJobResult result = run_saddle(options);
  EXPECT_EQ(result.out_path, options.out_path);
  const std::vector<std::string> rows = lines(test::read_bytes(options.out_path));
  ASSERT_EQ(rows.size(), 42u);
  EXPECT_EQ(rows[0], "i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm");
  EXPECT_EQ(rows[1], "0,0.000000000000,0.000000000,150.000000000,600.000000000,0.785398163397,0.000000000");
  // Row 11 of Table 1: 1.5708, 150.0000, 0.0000, 580.9475, 1.0381 (y is 9e-15 mm here: written without a sign).
  EXPECT_EQ(rows[11].rfind("10,1.570796326795,150.000000000,0.000000000,580.947501931,1.038078418540,", 0), 0u)
      << rows[11];
  EXPECT_EQ(rows[41].rfind("40,6.283185307180,", 0), 0u) << rows[41];
  EXPECT_EQ(dir.listing(), "saddle.csv\n");
}

TEST(SaddlePipeline, SameOptionsGiveTheSameBytes) {
  SaddleJobOptions options;
  options.saddle.geometry.pitch_rad = 1.0;
  options.saddle.geometry.offset_mm = -40.0;
  options.saddle.rule = constant_speed_rule(options.saddle.geometry);
  options.saddle.speed_mm_per_s = 250.0;
  EXPECT_EQ(options.saddle.rule, SaddleStepRule::kArcLength);
  const std::string a = saddle_csv(run_saddle(options).saddle);
  const std::string b = saddle_csv(run_saddle(options).saddle);
  EXPECT_EQ(a, b);
  EXPECT_EQ(a.find("-0.000000000,"), std::string::npos);
}

TEST(SaddlePipeline, ThePapersJointUsesThePapersVariableAngleRule) {
  SaddleGeometry geometry;
  EXPECT_EQ(constant_speed_rule(geometry), SaddleStepRule::kVariableAngle);
  geometry.offset_mm = 1.0;
  EXPECT_EQ(constant_speed_rule(geometry), SaddleStepRule::kArcLength);
}

TEST(SaddlePipeline, BadInputThrowsAndLeavesNoFile) {
  test::TempDir dir;
  SaddleJobOptions options;
  options.out_path = dir.file("saddle.csv");
  options.saddle.geometry.pipe_radius_mm = 700.0;  // r > R
  try {
    run_saddle(options);
    FAIL() << "r > R was accepted";
  } catch (const Error& e) {
    EXPECT_NE(
        std::string(e.what()).find("pipe radius r = 700 mm must not be larger than the cylinder radius R = 600 mm"),
        std::string::npos)
        << e.what();
  }
  EXPECT_EQ(dir.listing(), "");
}

TEST(SaddlePipeline, UnwritableOutputIsAnErrorNamingIt) {
  SaddleJobOptions options;
  options.out_path = "/nonexistent-dir/saddle.csv";
  try {
    run_saddle(options);
    FAIL() << "writing into a missing directory succeeded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/saddle.csv"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace conform
