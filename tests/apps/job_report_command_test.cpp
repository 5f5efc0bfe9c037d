// --report on sicp, tube-joint, saddle and weld-layers end to end, without a browser (report_browser_test.cpp renders
// the pages): a job that exits 1 still writes its report, and the verdict on it says why; bad input (exit 2) writes
// none. The pages themselves are tested in tests/pipelines/*_report_test.cpp.

#include <string>

#include <gtest/gtest.h>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

// The verdict line of a page: "fail: <why>" (its class and its text).
std::string verdict(const std::string& html) {
  const std::string open = "class=\"verdict ";
  const std::size_t at = html.find(open);
  if (at == std::string::npos) return "";
  const std::size_t cls_end = html.find('"', at + open.size());
  const std::size_t text = html.find('>', cls_end) + 1;
  return html.substr(at + open.size(), cls_end - at - open.size()) + ": " +
         html.substr(text, html.find('<', text) - text);
}

TEST(JobReportCommand, ExitOneWritesTheReportWithWhy) {
  const test::TempDir dir;
  // sicp: no segment has the edge points asked (--min-edge-points): every row untrusted, no trajectory, exit 1.
  auto g = test::run(CONFORM_EXE, {"generate", "plate", "--out", dir.file("p.ply"), "--scan-points", "8000",
                                   "--contour-spacing", "2", "--surface-edge", "4", "--quiet"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  auto r = test::run(
      CONFORM_EXE, {"sicp", "--contour", dir.file("p.contour.csv"), "--scan", dir.file("p.ply"), "--trajectory",
                    dir.file("p.trajectory.csv"), "--surface", dir.file("p.nominal.ply"), "--min-edge-points", "100000",
                    "--out-trajectory", dir.file("out.csv"), "--quiet", "--report", dir.file("sicp.html")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(test::read_bytes(dir.file("out.csv")), "");
  EXPECT_EQ(verdict(test::read_bytes(dir.file("sicp.html"))).rfind("fail: not trusted: ", 0), 0u)
      << verdict(test::read_bytes(dir.file("sicp.html")));
  // weld-layers: the reference 0.3 mm off (a registration error) is not refilled: exit 1.
  g = test::run(CONFORM_EXE,
                {"generate", "eroded", "--out", dir.file("b.csv"), "--rows", "21", "--cols", "31", "--length", "60",
                 "--width", "40", "--crater", "0,0,10,1.5", "--reference-offset", "0.3"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  r = test::run(CONFORM_EXE, {"weld-layers", "--eroded", dir.file("b.csv"), "--reference", dir.file("b.reference.csv"),
                              "--bead-spacing", "2", "--layer-height", "0.8", "--chord-error", "0.05", "--report",
                              dir.file("weld.html")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(verdict(test::read_bytes(dir.file("weld.html"))).find("fail: the eroded grid is offset"), std::string::npos)
      << verdict(test::read_bytes(dir.file("weld.html")));
}

TEST(JobReportCommand, TubeJointThatMissesMarksTheConditionAndBadInputWritesNothing) {
  const test::TempDir dir;
  const auto g = test::run(CONFORM_EXE, {"generate",      "tube-joint",
                                         "--out-leg",     dir.file("leg.ply"),
                                         "--out-stub",    dir.file("stub.ply"),
                                         "--out-truth",   dir.file("truth.csv"),
                                         "--leg-radius",  "300",
                                         "--stub-radius", "160",
                                         "--wall",        "10",
                                         "--edge",        "10",
                                         "--pitch-deg",   "60",
                                         "--offset",      "30",
                                         "--protrusion",  "540"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  // A protrusion of 100 mm puts the stub's end far from the leg: no intersection, exit 1.
  const auto r = test::run(
      CONFORM_EXE, {"tube-joint", "--leg", dir.file("leg.ply"), "--stub", dir.file("stub.ply"), "--pitch-deg", "60",
                    "--offset", "30", "--protrusion", "100", "--quiet", "--report", dir.file("tj.html")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(verdict(test::read_bytes(dir.file("tj.html"))).rfind("fail: [intersect] ", 0), 0u)
      << verdict(test::read_bytes(dir.file("tj.html")));
  // Bad input: no report, nothing left behind.
  const auto bad = test::run(CONFORM_EXE, {"saddle", "--R", "100", "--r", "150", "--start-pose-deg", "45", "--step-deg",
                                           "9", "--report", dir.file("saddle.html")});
  EXPECT_EQ(bad.exit_code, 2);
  const auto missing = test::run(CONFORM_EXE, {"profile", "--edge", dir.file("none.csv"), "--features",
                                               dir.file("none.csv"), "--report", dir.file("profile.html")});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(dir.listing(), "leg.ply\nstub.ply\ntj.html\ntruth.csv\n");
}

}  // namespace
}  // namespace conform
