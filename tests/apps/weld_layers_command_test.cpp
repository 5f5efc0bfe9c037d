// `conform generate eroded` and `conform weld-layers` end to end: the generated blade's crater is found and filled,
// JSON keys and CSV columns, bad grids (exit 2 naming file and row), no damage (exit 1), same bytes on a rerun.

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult run(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

// A small blade (60 x 40 mm, 2 mm grid) with one crater of radius 10 mm and depth 1.5 mm, generated once for all
// tests (each run of the executable costs ~0.4 s of start-up).
class WeldLayersCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    blade_dir_ = new test::TempDir;
    const auto r = run({"generate", "eroded", "--out", blade_dir_->file("blade.csv"), "--rows", "21", "--cols", "31",
                        "--length", "60", "--width", "40", "--crater", "0,0,10,1.5", "--noise", "0.005", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(blade_dir_->listing(), "blade.csv\nblade.reference.csv\nblade.rims.csv\n");
  }
  static void TearDownTestSuite() {
    delete blade_dir_;
    blade_dir_ = nullptr;
  }
  static std::string eroded() { return blade_dir_->file("blade.csv"); }
  static std::string reference() { return blade_dir_->file("blade.reference.csv"); }
  static test::TempDir* blade_dir_;
};

test::TempDir* WeldLayersCommand::blade_dir_ = nullptr;

std::vector<std::string> weld_args(const test::TempDir& dir, const std::string& eroded, const std::string& reference) {
  return {"weld-layers", "--eroded", eroded, "--reference", reference, "--bead-spacing", "2", "--layer-height", "0.8",
          "--chord-error", "0.05", "--torch-distance", "10", "--out", dir.file("paths.csv"), "--json"};
}

TEST_F(WeldLayersCommand, FillsTheGeneratedCrater) {
  test::TempDir dir;
  const auto r = run(weld_args(dir, eroded(), reference()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["layers"], 2);  // ceil(1.5 / 0.8)
  EXPECT_GT(j["paths"].get<int>(), 8);
  EXPECT_LT(j["spacing_error_pct_max"].get<double>(), 5.0);
  EXPECT_LE(j["chord_error_mm_max"].get<double>(), 0.05);
  EXPECT_GT(j["damage_coverage_pct"].get<double>(), 90.0);  // the uncovered rest: slivers at the regions' edges
  EXPECT_EQ(j["craters"].size(), 1u);
  EXPECT_FALSE(j["bias"]["significant"].get<bool>());
  EXPECT_EQ(j["outward_sign"], 1);
  EXPECT_EQ(j["warnings"].size(), 0u);
  EXPECT_TRUE(j["depth_threshold_estimated"].get<bool>());
  ASSERT_EQ(j["rims"].size(), 1u);
  const std::string csv = test::read_bytes(dir.file("paths.csv"));
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "layer,path,i,x_mm,y_mm,z_mm,nx,ny,nz");
  // Every layer-1 point lies inside the threshold rim rho_t = a sqrt(1 - cbrt(t / D)); 0.5 mm slack: near the rim the
  // crater deepens by only ~0.05 mm per mm, so 0.01 mm of noise and spline error move the rim by ~0.2 mm.
  std::istringstream in(csv.substr(csv.find('\n') + 1));
  for (std::string line; std::getline(in, line);) {
    double v[9];
    char comma;
    std::istringstream row(line);
    for (int k = 0; k < 9; ++k) row >> v[k] >> comma;
    if (v[0] == 1) {
      EXPECT_LT(std::hypot(v[3], v[4]), 10.0 * std::sqrt(1 - std::cbrt(j["depth_threshold_mm"].get<double>() / 1.5)) + 0.5);
    }
  }
  const auto again = run(weld_args(dir, eroded(), reference()));
  EXPECT_EQ(again.out, r.out);
  EXPECT_EQ(test::read_bytes(dir.file("paths.csv")), csv);
}

TEST_F(WeldLayersCommand, ReferenceRebuiltFromTheBorder) {
  test::TempDir dir;
  std::vector<std::string> args = weld_args(dir, eroded(), "");
  args.erase(args.begin() + 3, args.begin() + 5);  // no --reference
  args.push_back("--reference-from-border");
  const auto r = run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  // The blade is quadratic in x and y: the Coons patch of its border reproduces it, so the same crater is found.
  EXPECT_EQ(j["rims"].size(), 1u);
  EXPECT_EQ(j["layers"], 2);
  EXPECT_NEAR(j["max_depth_mm"].get<double>(), 1.5, 0.05);
  const auto neither = run({"weld-layers", "--eroded", eroded(), "--bead-spacing", "2", "--layer-height", "0.8",
                            "--chord-error", "0.05"});
  EXPECT_EQ(neither.exit_code, 2);
  EXPECT_NE(neither.err.find("--reference-from-border"), std::string::npos) << neither.err;
}

TEST_F(WeldLayersCommand, GenerateGivesTheSameBytesAndRims) {
  test::TempDir dir;
  const auto r = run({"generate", "eroded", "--out", dir.file("blade.csv"), "--rows", "21", "--cols", "31", "--length",
                      "60", "--width", "40", "--crater", "0,0,10,1.5", "--noise", "0.005"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"blade.csv", "blade.reference.csv", "blade.rims.csv"}) {
    EXPECT_EQ(test::read_bytes(dir.file(name)), test::read_bytes(blade_dir_->file(name))) << name;
  }
  const std::string rims = test::read_bytes(dir.file("blade.rims.csv"));
  EXPECT_EQ(rims.substr(0, rims.find('\n')), "crater,i,x_mm,y_mm,z_mm");
  EXPECT_NE(rims.find("\n1,0,10.000000,0.000000,"), std::string::npos);  // the rim rho = a, first point at angle 0
}

TEST_F(WeldLayersCommand, NoDamageExitsOne) {
  test::TempDir dir;
  // The reference against itself: nothing lies below the threshold.
  const auto r = run(weld_args(dir, reference(), reference()));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("no damage found"), std::string::npos) << r.err;
  EXPECT_EQ(dir.listing(), "");  // no paths.csv
}

TEST_F(WeldLayersCommand, BadGridsExitTwoNamingFileAndRow) {
  test::TempDir dir;
  const std::string reference = dir.file("ref.csv");
  test::write_bytes(reference, "row,col,x_mm,y_mm,z_mm\n0,0,0,0,0\n0,1,1,0,0\n1,0,0,1,0\n1,1,1,1,0\n");
  test::write_bytes(dir.file("holes.csv"), "row,col,x_mm,y_mm,z_mm\n0,0,0,0,0\n0,1,1,0,0\n0,2,2,0,0\n1,0,0,1,0\n1,2,2,1,0\n2,0,0,2,0\n2,1,1,2,0\n2,2,2,2,0\n");
  auto r = run(weld_args(dir, dir.file("holes.csv"), reference));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("holes.csv: hole in the grid: row 1, col 1"), std::string::npos) << r.err;
  test::write_bytes(dir.file("ragged.csv"), "row,col,x_mm,y_mm,z_mm\n0,0,0,0,0\n0,1,1,0,0\n0,2,2,0,0\n1,0,0,1,0\n1,1,1,1,0\n");
  r = run(weld_args(dir, dir.file("ragged.csv"), reference));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ragged.csv: ragged grid: row 1"), std::string::npos) << r.err;
  r = run({"generate", "eroded", "--out", dir.file("x.csv"), "--crater", "0,0,1"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--crater"), std::string::npos);
  EXPECT_EQ(test::read_bytes(dir.file("paths.csv")), "");
}

// Issue 17/18: a registration offset fails in check mode (exit 1 naming it) and is removed on request; a border
// crater is closed along the border; limits on layers, torch distance and outliers exit 2 naming the limit.
TEST_F(WeldLayersCommand, BiasBorderAndLimits) {
  test::TempDir dir;
  auto r = run({"generate", "eroded", "--out", dir.file("b.csv"), "--rows", "21", "--cols", "31", "--length", "60",
                "--width", "40", "--crater", "0,0,10,1.5", "--crater", "30,-20,9,1", "--reference-offset", "0.3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> args = weld_args(dir, dir.file("b.csv"), dir.file("b.reference.csv"));
  args[12] = "2";  // --torch-distance: 10 mm against the 1 mm crater's ~11 mm bowl makes Eq. (5)'s paths cross
  r = run(args);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("offset -0.2"), std::string::npos) << r.err;  // 0.3 mm along z: ~0.29 along the normal
  EXPECT_NE(r.err.find("--bias remove"), std::string::npos) << r.err;
  args.insert(args.end(), {"--bias", "remove"});
  r = run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["bias"]["removed"].get<bool>());
  ASSERT_EQ(j["craters"].size(), 2u);
  EXPECT_TRUE(j["craters"][1]["at_border"].get<bool>());
  EXPECT_GE(j["border_rims"].get<int>(), 1);
  EXPECT_GT(j["damage_coverage_pct"].get<double>(), 90.0);
  std::remove(dir.file("paths.csv").c_str());  // the failures below must not write it
  std::vector<std::string> thin = weld_args(dir, eroded(), reference());
  thin[8] = "0.001";  // --layer-height: 1500 layers
  r = run(thin);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("kMaxWeldLayers"), std::string::npos) << r.err;
  std::vector<std::string> far = weld_args(dir, eroded(), reference());
  far[12] = "1000";  // --torch-distance
  r = run(far);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("torch distance"), std::string::npos) << r.err;
  std::string grid = test::read_bytes(eroded());
  const std::size_t at = grid.find("\n10,15,");  // the centre node: z = 65535 (issue 18)
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = grid.find('\n', at + 1), last = grid.rfind(',', end);
  grid.replace(last + 1, end - last - 1, "65535");
  test::write_bytes(dir.file("spike.csv"), grid);
  r = run(weld_args(dir, dir.file("spike.csv"), reference()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("max_deviation_mm"), std::string::npos) << r.err;
  EXPECT_EQ(test::read_bytes(dir.file("paths.csv")), "");
}

}  // namespace
}  // namespace conform
