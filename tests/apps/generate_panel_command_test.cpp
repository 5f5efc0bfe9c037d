// `conform generate plate` / `generate nosecone` end to end: the six files, --json on stdout only, the same bytes
// for the same arguments, exit code 2 and no files for bad input.

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

const std::vector<std::string> kSmall = {"--scan-points", "5000", "--contour-spacing", "2", "--surface-edge", "5",
                                         "--quiet"};

test::RunResult generate(const std::string& shape, std::vector<std::string> args) {
  args.insert(args.begin(), {"generate", shape});
  args.insert(args.end(), kSmall.begin(), kSmall.end());
  return test::run(CONFORM_EXE, args);
}

TEST(GeneratePanelCommand, PlateWritesSixFilesAndPrintsJson) {
  test::TempDir dir;
  const auto r = generate("plate", {"--out", dir.file("p.ply"), "--round", "--seed", "3", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["scan_points"], 5000);
  EXPECT_EQ(j["truth"]["options"]["seed"], 3);
  EXPECT_EQ(j["truth"]["options"]["plate"]["round"], true);
  // A round porthole of 380 mm: perimeter 1193.8 mm in the plane, a little more on the curved plate.
  EXPECT_NEAR(j["perimeter_mm"].get<double>(), 1194.0, 4.0);
  EXPECT_EQ(dir.listing(), "p.contour.csv\np.nominal.ply\np.ply\np.trajectory.csv\np.truth.csv\np.truth.json\n");
  EXPECT_EQ(test::read_bytes(dir.file("p.truth.csv")).substr(0, 24), "x_mm,y_mm,z_mm,nx,ny,nz\n");
  EXPECT_EQ(test::read_bytes(dir.file("p.contour.csv")).substr(0, 15), "x_mm,y_mm,z_mm\n");
}

TEST(GeneratePanelCommand, NoseconeSameArgumentsGiveTheSameBytes) {
  test::TempDir a, b;
  for (const test::TempDir* dir : {&a, &b}) {
    ASSERT_EQ(generate("nosecone", {"--out", dir->file("n.ply"), "--corner-radius", "0", "--missing", "0.2"}).exit_code,
              0);
  }
  for (const char* name :
       {"n.ply", "n.nominal.ply", "n.contour.csv", "n.trajectory.csv", "n.truth.csv", "n.truth.json"}) {
    EXPECT_EQ(test::read_bytes(a.file(name)), test::read_bytes(b.file(name))) << name;
  }
}

TEST(GeneratePanelCommand, BadInputIsExitCodeTwoAndLeavesNoFile) {
  test::TempDir dir;
  const std::vector<std::vector<std::string>> bad = {{"--out", dir.file("p.stl")},
                                                     {"--out", dir.file("p.ply"), "--missing", "0.95"},
                                                     {"--out", dir.file("p.ply"), "--surface-edge", "0"}};
  for (const auto& args : bad) {
    const auto r = generate("plate", args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_EQ(generate("nosecone", {"--out", dir.file("n.ply"), "--corner-radius", "400"}).exit_code, 2);
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
