// Every command's outputs end to end (issue 18, docs/foundation.md "Outputs"): an output that is an input or is
// given twice is exit 2 before any work, a multi-file command commits all outputs or none and never loses a file it
// did not create, and `-` streams to standard output.

#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult conform(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A small tube patch as scan and reference, made once.
const test::TempDir& patch() {
  static const test::TempDir* dir = [] {
    auto* d = new test::TempDir();
    const std::vector<std::string> args = {"generate", "tube",      "--quiet", "--radius", "100", "--length",
                                           "40",       "--arc-deg", "40",      "--edge",   "4",   "--out"};
    std::vector<std::string> ref = args, scan = args;
    ref.push_back(d->file("nominal.ply"));
    scan.push_back(d->file("scan.ply"));
    EXPECT_EQ(conform(ref).exit_code, 0);
    EXPECT_EQ(conform(scan).exit_code, 0);
    return d;
  }();
  return *dir;
}

// Issue 18: this exited 2 and deleted scan.ply.
TEST(Outputs, CompareFailingOnTheHistogramLeavesTheScanThatWasGivenAsTheMap) {
  test::TempDir dir;
  const std::string scan = dir.file("scan.ply"), copy = test::read_bytes(patch().file("scan.ply"));
  test::write_bytes(scan, copy);
  const auto r = conform({"compare", "--scan", patch().file("scan.ply"), "--reference", patch().file("nominal.ply"),
                          "--out-deviation", scan, "--out-histogram", dir.file("nodir/h.png")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(test::read_bytes(scan), copy);
  EXPECT_EQ(dir.listing(), "scan.ply\n");
}

// Issue 18: tube-joint lost an existing path.csv when a later output failed.
TEST(Outputs, TubeJointFailingOnALaterOutputKeepsTheExistingPath) {
  test::TempDir dir;
  const auto made = conform({"generate",       "tube-joint",
                             "--out-leg",      dir.file("leg.ply"),
                             "--out-stub",     dir.file("stub.ply"),
                             "--out-truth",    dir.file("truth.csv"),
                             "--leg-radius",   "300",
                             "--stub-radius",  "160",
                             "--wall",         "10",
                             "--edge",         "12",
                             "--truth-points", "90",
                             "--pitch-deg",    "90",
                             "--offset",       "0",
                             "--json"});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  std::ostringstream protrusion;
  protrusion.precision(17);
  protrusion << nlohmann::json::parse(made.out)["protrusion_mm"].get<double>();
  test::write_bytes(dir.file("path.csv"), "the previous path\n");
  const auto r = conform({"tube-joint", "--leg", dir.file("leg.ply"), "--stub", dir.file("stub.ply"), "--step-deg",
                          "10", "--pitch-deg", "90", "--offset", "0", "--protrusion", protrusion.str(), "--out-path",
                          dir.file("path.csv"), "--out-cut", dir.file("nodir/cut.csv")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "nodir/cut.csv")) << r.err;
  EXPECT_EQ(test::read_bytes(dir.file("path.csv")), "the previous path\n");
  EXPECT_EQ(dir.listing(), "leg.ply\npath.csv\nstub.ply\ntruth.csv\n");
}

TEST(Outputs, AnOutputThatIsAnInputIsExitTwoBeforeAnyWork) {
  test::TempDir dir;
  test::write_bytes(dir.file("scan.ply"), "not even a ply: refused before it is read");
  test::write_bytes(dir.file("grid.csv"), "row,col,x_mm,y_mm,z_mm\n");
  const std::vector<std::vector<std::string>> runs = {
      {"compare", "--scan", dir.file("scan.ply"), "--reference", dir.file("grid.csv"), "--out-deviation",
       dir.path() + "/./scan.ply"},
      {"align", "--scan", dir.file("scan.ply"), "--reference", dir.file("grid.csv"), "--out-aligned",
       dir.file("scan.ply")},
      {"weld-layers", "--eroded", dir.file("grid.csv"), "--chord-error", "0.1", "--bead-spacing", "5", "--layer-height",
       "2", "--out", dir.file("grid.csv")},
      {"fit-cylinder", "--input", dir.file("scan.ply"), "--out", dir.file("scan.ply")},
      {"profile", "--edge", dir.file("grid.csv"), "--features", dir.file("scan.ply"), "--out", dir.file("grid.csv")},
  };
  for (const auto& args : runs) {
    const auto r = conform(args);
    EXPECT_EQ(r.exit_code, 2) << args[0] << ": " << r.err;
    EXPECT_TRUE(contains(r.err, "is the input")) << args[0] << ": " << r.err;
  }
  EXPECT_EQ(test::read_bytes(dir.file("scan.ply")), "not even a ply: refused before it is read");
  EXPECT_EQ(test::read_bytes(dir.file("grid.csv")), "row,col,x_mm,y_mm,z_mm\n");
  EXPECT_EQ(dir.listing(), "grid.csv\nscan.ply\n");
}

TEST(Outputs, TheSamePathGivenTwiceIsExitTwoAndWritesNothing) {
  test::TempDir dir;
  const auto r = conform({"generate", "tube-joint", "--out-leg", dir.file("x.ply"), "--out-stub", dir.file("x.ply"),
                          "--out-truth", dir.file("t.csv")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "given as two outputs")) << r.err;
  EXPECT_EQ(dir.listing(), "");
}

// Issue 18: `--out /dev/stdout` replaced /dev/stdout by a regular file (as root). Both stream now.
TEST(Outputs, DashAndDevStdoutStreamToStandardOutput) {
  const auto dev = conform(
      {"saddle", "--R", "600", "--r", "150", "--start-pose-deg", "45", "--step-deg", "90", "--out", "/dev/stdout"});
  ASSERT_EQ(dev.exit_code, 0) << dev.err;
  EXPECT_TRUE(contains(dev.out, "i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm\n0,")) << dev.out;
  const auto r = conform(
      {"saddle", "--R", "600", "--r", "150", "--start-pose-deg", "45", "--step-deg", "90", "--json", "--out", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "i,theta_rad,x_mm,y_mm,z_mm,pose_rad,step_mm\n0,")) << r.out;
}

}  // namespace
}  // namespace conform
