// `conform sicp` end to end on a small generated plate (small enough for sanitizer builds): exit 0, --json with "segments", "rms_mm" per segment and
// overall, "converged"; the output trajectory has the input's rows in order; the same bytes on a rerun; a mesh
// contour (its boundary on the scan); exit code 2 and no output for bad input.

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

class SicpCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto r = test::run(CONFORM_EXE, {"generate", "plate", "--out", dir_.file("p.ply"), "--scan-points", "8000",
                                           "--contour-spacing", "2", "--surface-edge", "4", "--quiet"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  test::RunResult sicp(std::vector<std::string> args, const std::string& trajectory = "p.trajectory.csv") {
    args.insert(args.begin(), {"sicp", "--contour", dir_.file("p.contour.csv"), "--scan", dir_.file("p.ply"),
                               "--trajectory", dir_.file(trajectory), "--quiet"});
    return test::run(CONFORM_EXE, args);
  }
  std::size_t rows(const std::string& path) {
    std::istringstream in(test::read_bytes(path));
    std::size_t n = 0;
    for (std::string line; std::getline(in, line);) ++n;
    return n - 1;  // the header
  }
  test::TempDir dir_;
};

TEST_F(SicpCommandTest, JsonAndTrajectory) {
  const auto r = sicp({"--surface", dir_.file("p.nominal.ply"), "--truth", dir_.file("p.truth.csv"), "--out-trajectory",
                       dir_.file("out.csv"), "--out-rows", dir_.file("rows.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["converged"], true);
  EXPECT_EQ(j["trusted"], true);
  EXPECT_EQ(j["checks"]["blind_segments"].size(), 0u);
  EXPECT_NEAR(j["checks"]["noise_mm"].get<double>(), 0.05, 0.02);  // the generator's sigma
  EXPECT_EQ(j["model"], "sicp");
  ASSERT_GT(j["segments"].size(), 20u);  // ~1015 mm in segments of at most 40 mm
  for (const auto& s : j["segments"]) EXPECT_LT(s["rms_mm"].get<double>(), 0.2);
  EXPECT_LT(j["rms_mm"].get<double>(), 0.1);
  EXPECT_LT(j["error"]["path_mean_mm"].get<double>(), 0.1);  // noise 0.05 mm; measured ~0.03
  EXPECT_EQ(rows(dir_.file("out.csv")), rows(dir_.file("p.trajectory.csv")));
  EXPECT_EQ(test::read_bytes(dir_.file("out.csv")).substr(0, 24), "x_mm,y_mm,z_mm,nx,ny,nz\n");
  // Per row: the correction across the edge, along the tool axis and along the path, and the row's confidence.
  EXPECT_EQ(rows(dir_.file("rows.csv")), rows(dir_.file("p.trajectory.csv")));
  // ... its scan points near the edge and the unscanned stretch it lies in (none here).
  const std::string header = "row,across_mm,axis_mm,along_mm,confidence,contour_distance_mm,edge_points,gap_mm\n1,";
  EXPECT_EQ(test::read_bytes(dir_.file("rows.csv")).substr(0, header.size()), header);
  EXPECT_EQ(j["checks"]["unmeasured_rows"].get<int>(), 0);
  const auto again = sicp({"--surface", dir_.file("p.nominal.ply"), "--out-trajectory", dir_.file("again.csv")});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(test::read_bytes(dir_.file("again.csv")), test::read_bytes(dir_.file("out.csv")));
}

TEST_F(SicpCommandTest, RigidProjectionAndMeshContour) {
  // Every model gets S-ICP's checks, stretch by stretch: on the sagging plate one rigid transform (and the rigid one
  // plus a height field) leaves every segment's residuals far above the noise, and the path is refused.
  for (const char* model : {"rigid", "projection"}) {
    const auto r = sicp({"--surface", dir_.file("p.nominal.ply"), "--model", model, "--json", "--out-trajectory",
                         dir_.file("never.csv")});
    ASSERT_EQ(r.exit_code, 1) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["model"], model);
    EXPECT_GT(j["segments"].size(), 10u);
    EXPECT_GT(j["checks"]["outlier_segments"].size(), 10u);
    EXPECT_FALSE(std::filesystem::exists(dir_.file("never.csv")));
  }
  // The nominal mesh as the contour: its boundary loop on the scan (the flank's bottom edge) and its own surface.
  auto args = std::vector<std::string>{"sicp",
                                       "--contour",
                                       dir_.file("p.nominal.ply"),
                                       "--scan",
                                       dir_.file("p.ply"),
                                       "--trajectory",
                                       dir_.file("p.trajectory.csv"),
                                       "--quiet",
                                       "--json"};
  const auto r = test::run(CONFORM_EXE, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // Two loops: the band's outer rim and the flank's bottom edge; the one on the scan is taken.
  EXPECT_EQ(j["contour_source"].get<std::string>().substr(0, 13), "mesh boundary");
  EXPECT_NE(j["contour_source"].get<std::string>().find("of 2 (closed)"), std::string::npos);
  EXPECT_EQ(j["converged"], true);
}

TEST_F(SicpCommandTest, BadInputIsExitCodeTwoAndWritesNothing) {
  test::write_bytes(dir_.file("bad.csv"), "x_mm,y_mm,z_mm,nx,ny,nz\n1,2,3,0,0,2\n");
  const std::string surface = dir_.file("p.nominal.ply");
  const auto bad_normal = sicp({"--surface", surface, "--out-trajectory", dir_.file("o.csv")}, "bad.csv");
  EXPECT_EQ(bad_normal.exit_code, 2);
  EXPECT_NE(bad_normal.err.find("bad.csv:2"), std::string::npos) << bad_normal.err;
  test::write_bytes(dir_.file("nocol.csv"), "x,y,z\n1,2,3\n");
  const auto no_column = sicp({"--surface", surface, "--out-trajectory", dir_.file("o.csv")}, "nocol.csv");
  EXPECT_EQ(no_column.exit_code, 2);
  EXPECT_NE(no_column.err.find("nocol.csv"), std::string::npos);
  const auto no_surface = sicp({"--surface", dir_.file("missing.ply"), "--out-trajectory", dir_.file("o.csv")});
  EXPECT_EQ(no_surface.exit_code, 2);
  EXPECT_NE(no_surface.err.find("missing.ply"), std::string::npos);
  EXPECT_EQ(sicp({"--model", "spline"}).exit_code, 2);
  EXPECT_EQ(sicp({"--surface", surface, "--overlap", "1.5", "--out-trajectory", dir_.file("o.csv")}).exit_code, 2);
  const auto misfit =
      sicp({"--surface", surface, "--max-normal-error-deg", "0", "--out-trajectory", dir_.file("o.csv")});
  EXPECT_EQ(misfit.exit_code, 2);
  EXPECT_NE(misfit.err.find("tool normal error must be > 0 deg"), std::string::npos) << misfit.err;
  const auto dent = sicp({"--surface", surface, "--max-dent-slope-deg", "0", "--out-trajectory", dir_.file("o.csv")});
  EXPECT_EQ(dent.exit_code, 2);
  EXPECT_NE(dent.err.find("dent slope limit must be > 0 deg"), std::string::npos) << dent.err;
  const auto gap = sicp({"--surface", surface, "--max-edge-gap", "-1", "--out-trajectory", dir_.file("o.csv")});
  EXPECT_EQ(gap.exit_code, 2);
  EXPECT_NE(gap.err.find("largest bridged gap"), std::string::npos) << gap.err;
  // Contour-only S-ICP (a CSV contour without --surface) is refused, naming the option to give.
  const auto contour_only = sicp({"--out-trajectory", dir_.file("o.csv")});
  EXPECT_EQ(contour_only.exit_code, 2);
  EXPECT_NE(contour_only.err.find("--surface"), std::string::npos) << contour_only.err;
  // Bounded work (issue 18): a segment length below 1 mm, and a contour point 4294967295 mm away (its 8.6e9 mm would
  // need ~2e8 segments), are refused before anything is allocated for the segments, naming the limit.
  const auto tiny = sicp({"--surface", surface, "--segment-length", "0.0001", "--out-trajectory", dir_.file("o.csv")});
  EXPECT_EQ(tiny.exit_code, 2);
  EXPECT_NE(tiny.err.find("segment length must be in [1, 1e5] mm"), std::string::npos) << tiny.err;
  std::string contour = test::read_bytes(dir_.file("p.contour.csv"));
  contour.insert(contour.find('\n') + 1, "9000000,0,0\n");  // within +-1e7 (csv.h), 9 km off
  test::write_bytes(dir_.file("far_point.csv"), contour);
  auto args = std::vector<std::string>{"sicp",         "--contour", dir_.file("far_point.csv"),
                                       "--scan",       dir_.file("p.ply"),
                                       "--trajectory", dir_.file("p.trajectory.csv"),
                                       "--surface",    surface,
                                       "--quiet",      "--out-trajectory",
                                       dir_.file("o.csv")};
  const auto huge = test::run(CONFORM_EXE, args);
  EXPECT_EQ(huge.exit_code, 2);
  EXPECT_NE(huge.err.find("max_segments"), std::string::npos) << huge.err;
  EXPECT_TRUE(test::read_bytes(dir_.file("o.csv")).empty());
}

// A trajectory 100 mm off the contour (another part, or another frame): the job runs but refuses the path (exit 1),
// says why in the text and the JSON, and writes nothing.
TEST_F(SicpCommandTest, TrajectoryFarFromTheContourIsExitOne) {
  std::istringstream in(test::read_bytes(dir_.file("p.trajectory.csv")));
  std::string line, shifted;
  std::getline(in, line);
  shifted = line + "\n";
  while (std::getline(in, line)) {
    const std::size_t comma = line.find(',');
    shifted += std::to_string(std::stod(line.substr(0, comma)) + 100.0) + line.substr(comma) + "\n";
  }
  test::write_bytes(dir_.file("far.csv"), shifted);
  const auto r =
      sicp({"--surface", dir_.file("p.nominal.ply"), "--json", "--out-trajectory", dir_.file("o.csv")}, "far.csv");
  EXPECT_EQ(r.exit_code, 1);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["trusted"], false);
  EXPECT_GT(j["checks"]["far_rows"].get<int>(), 0);
  EXPECT_NE(r.err.find("from the contour"), std::string::npos) << r.err;
  EXPECT_TRUE(test::read_bytes(dir_.file("o.csv")).empty());
}

}  // namespace
}  // namespace conform
