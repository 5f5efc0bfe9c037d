// `conform generate tube` end to end: files, --json on stdout only, same bytes for the same arguments, exit code 2
// and no files for bad input, and the bundled example regenerates byte for byte from the command in its README.

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult generate_tube(const std::vector<std::string>& args) {
  std::vector<std::string> all{"generate", "tube", "--quiet"};
  all.insert(all.end(), args.begin(), args.end());
  return test::run(CONFORM_EXE, all);
}

TEST(GenerateTubeCommand, WritesMeshAndTruthAndPrintsJson) {
  test::TempDir dir;
  const std::string out = dir.file("leg.ply");
  const auto r = generate_tube({"--out",
                                out,
                                "--radius",
                                "1000",
                                "--length",
                                "600",
                                "--arc-deg",
                                "60",
                                "--vertices",
                                "20000",
                                "--noise",
                                "0.05",
                                "--bump=-10,0,-1.5,40",
                                "--bump",
                                "10,100,1,30",
                                "--outliers",
                                "0.001",
                                "--axis-direction",
                                "1,0,0",
                                "--seed",
                                "5",
                                "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // one JSON object, nothing else on stdout
  EXPECT_EQ(j["mesh"], out);
  EXPECT_EQ(j["truth_file"], dir.file("leg.truth.json"));
  EXPECT_NEAR(j["vertices"].get<double>(), 20000.0, 600.0);
  EXPECT_EQ(j["outliers"], 20);
  EXPECT_EQ(j["truth"]["seed"], 5);
  EXPECT_EQ(j["truth"]["deformations"]["bumps"].size(), 2u);
  EXPECT_EQ(j["truth"]["geometry"]["axis_direction"], nlohmann::json({1.0, 0.0, 0.0}));
  EXPECT_FALSE(j["truth"]["scanner"]["outliers"].contains("indices"));  // those stay in the file
  const auto truth = nlohmann::json::parse(test::read_bytes(dir.file("leg.truth.json")));
  EXPECT_EQ(truth["scanner"]["outliers"]["indices"].size(), 20u);
  EXPECT_EQ(dir.listing(), "leg.ply\nleg.truth.json\n");
}

TEST(GenerateTubeCommand, SameArgumentsGiveTheSameBytes) {
  test::TempDir a;
  test::TempDir b;
  const std::vector<std::string> args = {"--arc-deg", "120",     "--edge",  "6",      "--inner",
                                         "--ovality", "0.5",     "--noise", "0.03",   "--noise-type",
                                         "uniform",   "--holes", "2",       "--seed", "77"};
  for (const test::TempDir* dir : {&a, &b}) {
    std::vector<std::string> all = args;
    all.insert(all.end(), {"--out", dir->file("scan.stl")});
    ASSERT_EQ(generate_tube(all).exit_code, 0);
  }
  EXPECT_EQ(test::read_bytes(a.file("scan.stl")), test::read_bytes(b.file("scan.stl")));
  EXPECT_EQ(test::read_bytes(a.file("scan.truth.json")), test::read_bytes(b.file("scan.truth.json")));
}

TEST(GenerateTubeCommand, BadInputIsExitCodeTwoAndLeavesNoFile) {
  test::TempDir dir;
  const std::vector<std::vector<std::string>> bad = {
      {"--out", dir.file("t.obj")},
      {"--out", dir.file("t.ply"), "--radius", "-1"},
      {"--out", dir.file("t.ply"), "--bump", "1,2,3"},
      {"--out", dir.file("t.ply"), "--hole", "0,x,5"},
      {"--out", dir.file("t.ply"), "--axis-direction", "0,0,0"},
      {"--out", dir.file("t.ply"), "--outliers", "1.5"},
      {"--out", dir.file("t.ply"), "--noise-type", "pink"},
      {"--out", dir.file("t.ply"), "--edge", "2", "--vertices", "1000"},
      {"--radius", "100"},
  };
  for (const auto& args : bad) {
    const auto r = generate_tube(args);
    EXPECT_EQ(r.exit_code, 2) << args.back() << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_EQ(dir.listing(), "");
}

// datasets/examples/README.md gives this command; a change to the generator or the writers shows up here.
TEST(GenerateTubeCommand, BundledExampleRegeneratesByteForByte) {
  test::TempDir dir;
  const auto r = generate_tube({"--out",
                                dir.file("tube_patch.ply"),
                                "--radius",
                                "150",
                                "--length",
                                "200",
                                "--arc-deg",
                                "90",
                                "--edge",
                                "4",
                                "--ovality",
                                "0.3",
                                "--ovality-azimuth-deg",
                                "20",
                                "--seam-height",
                                "0.4",
                                "--seam-width",
                                "20",
                                "--seam-azimuth-deg",
                                "10",
                                "--noise",
                                "0.02",
                                "--normals",
                                "--seed",
                                "1"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string examples = std::string(CONFORM_SOURCE_DIR) + "/datasets/examples/";
  EXPECT_EQ(test::read_bytes(dir.file("tube_patch.ply")), test::read_bytes(examples + "tube_patch.ply"));
  EXPECT_EQ(test::read_bytes(dir.file("tube_patch.truth.json")), test::read_bytes(examples + "tube_patch.truth.json"));
}

}  // namespace
}  // namespace conform
