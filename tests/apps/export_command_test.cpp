// `conform export` end to end: a saddle path written by `conform saddle` exported in every format, the split, the same
// bytes twice, and bad input (exit 2, the file and the problem named, nothing written).

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult conform(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

class ExportCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto r = conform({"saddle", "--R", "600", "--r", "150", "--start-pose-deg", "45", "--step-deg", "3",
                            "--out", dir.file("seam.csv")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  test::RunResult exporting(std::vector<std::string> more) {
    std::vector<std::string> args = {"export", "--path", dir.file("seam.csv")};
    args.insert(args.end(), more.begin(), more.end());
    return conform(args);
  }
  test::TempDir dir;
};

TEST_F(ExportCommand, EveryFormatWritesItsProgram) {
  const std::vector<std::pair<std::string, std::string>> formats = {
      {"krl", "weld.src"}, {"rapid", "weld.mod"}, {"urscript", "weld.script"}, {"fanuc", "weld.ls"},
      {"val3", "weld.pgx"}, {"gcode", "weld.nc"}, {"csv", "weld.csv"}};
  for (const auto& [format, file] : formats) {
    SCOPED_TRACE(format);
    const auto r = exporting({"--format", format, "--out", dir.file(file), "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto json = nlohmann::json::parse(r.out);
    EXPECT_EQ(json["job"], "saddle");
    EXPECT_EQ(json["frames"], 121);
    EXPECT_EQ(json["targets"], 123);  // with approach and retract
    // 3 deg steps on the paper's seam: the torch turns by at most 3.7 deg per step.
    EXPECT_LT(json["max_orientation_step_deg"].get<double>(), 4.0);
    EXPECT_FALSE(test::read_bytes(dir.file(file)).empty());
  }
  EXPECT_NE(test::read_bytes(dir.file("weld.dtx")).find("pointRx"), std::string::npos);
  EXPECT_NE(test::read_bytes(dir.file("weld.nc")).find("TRAORI"), std::string::npos);
}

TEST_F(ExportCommand, SameBytesTwiceAndTheSplit) {
  ASSERT_EQ(exporting({"--format", "krl", "--out", dir.file("a.src")}).exit_code, 0);
  ASSERT_EQ(exporting({"--format", "krl", "--out", dir.file("b.src"), "--name", "a"}).exit_code, 0);
  EXPECT_EQ(test::read_bytes(dir.file("a.src")), test::read_bytes(dir.file("b.src")));
  const auto r = exporting({"--format", "rapid", "--out", dir.file("p.mod"), "--max-points", "50"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(dir.listing(), "a.src\nb.src\np.mod\np_1.mod\np_2.mod\np_3.mod\nseam.csv\n");
  EXPECT_NE(test::read_bytes(dir.file("p.mod")).find("p_3_run;"), std::string::npos);
}

TEST_F(ExportCommand, BadInputExitsTwoNamingTheFileAndWritesNothing) {
  test::write_bytes(dir.file("nocols.csv"), "x_mm,y_mm,z_mm\n0,0,0\n");
  test::write_bytes(dir.file("nan.csv"), "x_mm,y_mm,z_mm,nx,ny,nz\n0,0,0,0,0,1\n1,0,nan,0,0,1\n");
  test::write_bytes(dir.file("scaled.txt"), "2 0 0 0\n0 2 0 0\n0 0 2 0\n0 0 0 1\n");
  const std::string before = dir.listing();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"export", "--path", dir.file("nocols.csv"), "--format", "krl", "--out", dir.file("x.src")}, "nocols.csv"},
      {{"export", "--path", dir.file("nan.csv"), "--format", "krl", "--out", dir.file("x.src")}, "nan.csv:3"},
      {{"export", "--path", dir.file("seam.csv"), "--format", "krl", "--out", dir.file("x.src"), "--frame",
        dir.file("scaled.txt")},
       "scaled.txt"},
      {{"export", "--path", dir.file("seam.csv"), "--format", "abb", "--out", dir.file("x.src")}, "abb"},
      {{"export", "--path", dir.file("seam.csv"), "--format", "krl", "--out", dir.file("9x.src")}, "--name"},
      {{"export", "--path", dir.file("seam.csv"), "--format", "krl", "--out", dir.file("seam.csv")}, "input"},
  };
  for (const Case& c : cases) {
    const auto r = conform(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(dir.listing(), before) << c.message;
  }
}

}  // namespace
}  // namespace conform
