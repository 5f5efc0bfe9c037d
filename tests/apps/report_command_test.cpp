// --report FILE.html end to end, without a browser (report_browser_test.cpp renders the pages): written also when
// the job exits 1 (the verdict says why), never on exit 2 (bad input: no file, no temporary left), refused unless
// .html, and the same bytes for the same input once the date is fixed (CONFORM_REPORT_DATE).

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

TEST(ReportCommand, WrittenOnExitOneWithTheVerdictNotOnExitTwo) {
  test::TempDir dir;
  std::string plane;
  for (int i = 0; i < 30; ++i) {
    for (int j = 0; j < 30; ++j) plane += std::to_string(2 * i) + " " + std::to_string(2 * j) + " 0\n";
  }
  test::write_bytes(dir.file("plane.xyz"), plane);
  const auto r = test::run(CONFORM_EXE, {"fit-cylinder", "--input", dir.file("plane.xyz"), "--quiet", "--report",
                                         dir.file("plane.html")});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const std::string html = test::read_bytes(dir.file("plane.html"));
  EXPECT_NE(html.find("class=\"verdict fail\" id=\"conform-verdict\">no cylinder: "), std::string::npos);

  const auto bad = test::run(CONFORM_EXE, {"compare", "--scan", dir.file("missing.ply"), "--reference",
                                           dir.file("plane.xyz"), "--report", dir.file("bad.html")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(dir.listing(), "plane.html\nplane.xyz\n");
  const auto txt = test::run(CONFORM_EXE, {"fit-cylinder", "--input", dir.file("plane.xyz"), "--report",
                                           dir.file("r.txt")});
  EXPECT_EQ(txt.exit_code, 2);
  EXPECT_NE(txt.err.find("the report must be .html"), std::string::npos) << txt.err;
}

TEST(ReportCommand, SameInputSameBytesWithAFixedDate) {
  test::TempDir dir;
  const auto g = test::run(CONFORM_EXE, {"generate", "tube", "--quiet", "--radius", "50", "--length", "40",
                                         "--arc-deg", "90", "--edge", "2", "--noise", "0.02", "--out",
                                         dir.file("tube.ply")});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  ::setenv("CONFORM_REPORT_DATE", "2026-01-01 00:00 UTC", 1);
  for (const char* name : {"a.html", "b.html"}) {
    const auto r = test::run(CONFORM_EXE, {"fit-cylinder", "--input", dir.file("tube.ply"), "--quiet", "--report",
                                           dir.file(name)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  ::unsetenv("CONFORM_REPORT_DATE");
  const std::string a = test::read_bytes(dir.file("a.html"));
  EXPECT_EQ(a, test::read_bytes(dir.file("b.html")));
  EXPECT_NE(a.find("<td>date</td><td>2026-01-01 00:00 UTC</td>"), std::string::npos);
}

}  // namespace
}  // namespace conform
