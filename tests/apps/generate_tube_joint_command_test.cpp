// `conform generate tube-joint` end to end: three files or none, --json, the same bytes on a rerun, exit 2 for bad
// input.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

std::vector<std::string> small(const test::TempDir& dir) {
  return {"generate",       "tube-joint",
          "--out-leg",      dir.file("leg.ply"),
          "--out-stub",     dir.file("stub.ply"),
          "--out-truth",    dir.file("truth.csv"),
          "--leg-radius",   "300",
          "--stub-radius",  "160",
          "--wall",         "10",
          "--edge",         "10",
          "--truth-points", "360",
          "--pitch-deg",    "60",
          "--offset",       "30",
          "--ovality-pct",  "1",
          "--peaking",      "3",
          "--noise",        "0.2"};
}

TEST(GenerateTubeJointCommand, WritesTheThreeFilesAndTheSameBytesOnARerun) {
  test::TempDir dir;
  auto args = small(dir);
  args.push_back("--json");
  const test::RunResult r = test::run(CONFORM_EXE, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["truth_points"], 360);
  EXPECT_NEAR(j["stub_inner_radius_mm"].get<double>(), 150.0, 1e-12);
  EXPECT_GT(j["protrusion_mm"].get<double>(), 300.0);
  const std::string truth = test::read_bytes(dir.file("truth.csv"));
  EXPECT_EQ(truth.substr(0, truth.find('\n')), "phi_rad,x_mm,y_mm,z_mm");
  const std::string leg = test::read_bytes(dir.file("leg.ply"));
  ASSERT_EQ(test::run(CONFORM_EXE, args).exit_code, 0);
  EXPECT_EQ(test::read_bytes(dir.file("leg.ply")), leg);
  EXPECT_EQ(test::read_bytes(dir.file("truth.csv")), truth);
}

// The automatic protrusion leaves the stub's distal end as far clear of the leg as the help says: the stub's outer
// radius 160 mm at 60 deg pitch on a 300 mm leg reaches (300 + 160 cos 60) / sin 60 from the leg's axis.
TEST(GenerateTubeJointCommand, AutomaticProtrusionIsTheClearanceTheHelpStates) {
  const test::RunResult help = test::run(CONFORM_EXE, {"generate", "tube-joint", "--help"});
  ASSERT_EQ(help.exit_code, 0);
  const std::size_t at = help.out.find("automatic (");
  ASSERT_NE(at, std::string::npos) << help.out;
  const double clearance = std::stod(help.out.substr(at + 11));
  EXPECT_GT(clearance, 0.0);
  test::TempDir dir;
  auto args = small(dir);
  args.push_back("--json");
  const test::RunResult r = test::run(CONFORM_EXE, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double pitch = M_PI / 3.0;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["protrusion_mm"].get<double>(),
              (300.0 + 160.0 * std::cos(pitch)) / std::sin(pitch) + clearance, 1e-9);
}

TEST(GenerateTubeJointCommand, BadInputIsExitTwoAndLeavesNoFile) {
  test::TempDir dir;
  auto args = small(dir);
  args[7] = dir.file("truth.txt");  // --out-truth must be .csv
  test::RunResult r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("truth.txt"), std::string::npos) << r.err;
  args = small(dir);
  args[11] = "400";  // --stub-radius: bigger than the leg
  r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("leg radius"), std::string::npos) << r.err;
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
