// `conform export` end to end: a saddle path written by `conform saddle` exported in every format, the split, the same
// bytes twice, and bad input (exit 2, the file and the problem named, nothing written).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <utility>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conform/core/csv.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult conform(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

using Table = CsvTable;

Table table(const std::string& text) { return parse_csv(text, "test.csv"); }

double number(const Table& t, std::size_t row, const std::string& name) { return t.number(row, t.column(name)); }

Eigen::Vector3d vec(const Table& t, std::size_t row, const std::string& a, const std::string& b, const std::string& c) {
  return {number(t, row, a), number(t, row, b), number(t, row, c)};
}

// The tool axis z of an exported frames row: the third column of the quaternion's matrix, written out.
Eigen::Vector3d tool_axis(const Table& frames, std::size_t row) {
  const double w = number(frames, row, "qw"), x = number(frames, row, "qx"), y = number(frames, row, "qy"),
               z = number(frames, row, "qz");
  return {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
}

// The job's file and its frames: row by row the same positions, z = -n.
void expect_minus_normal(const Table& job, const Table& frames, const std::vector<std::size_t>& job_rows) {
  ASSERT_EQ(frames.rows(), job_rows.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < job_rows.size(); ++k) {
    const std::size_t r = job_rows[k];
    EXPECT_LT((vec(frames, k, "x_mm", "y_mm", "z_mm") - vec(job, r, "x_mm", "y_mm", "z_mm")).norm(), 1e-9);
    worst = std::max(worst, (tool_axis(frames, k) + vec(job, r, "nx", "ny", "nz").normalized()).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

class ExportCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto r = conform({"saddle", "--R", "600", "--r", "150", "--start-pose-deg", "45", "--step-deg", "3", "--out",
                            dir.file("seam.csv")});
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
      {"krl", "weld.src"},  {"rapid", "weld.mod"}, {"urscript", "weld.script"}, {"fanuc", "weld.ls"},
      {"val3", "weld.pgx"}, {"gcode", "weld.nc"},  {"csv", "weld.csv"}};
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
  EXPECT_EQ(dir.listing(), "a.src\nb.src\np.mod\np_1.mod\np_2.mod\np_3.mod\nseam.csv\n");  // before f.csv
  EXPECT_NE(test::read_bytes(dir.file("p.mod")).find("p_3_run;"), std::string::npos);
  // The frames csv read back as a path: the same motion points (its approach rows left out, made again).
  ASSERT_EQ(exporting({"--format", "csv", "--out", dir.file("f.csv")}).exit_code, 0);
  const auto again =
      conform({"export", "--path", dir.file("f.csv"), "--format", "krl", "--out", dir.file("g.src"), "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(nlohmann::json::parse(again.out)["job"], "frames");
  EXPECT_EQ(nlohmann::json::parse(again.out)["targets"], 123);
}

// The weld-layers, profile, sicp and tube-joint jobs' own files, written by the jobs from generated data: every frame
// sits on its row's point with z = -n (the normal of weld-layers points towards the torch, the profile's is the web
// normal) or z = +d (tube-joint's cutting direction).
TEST_F(ExportCommand, JobFilesGiveTheirToolAxes) {
  ASSERT_EQ(conform({"generate", "eroded", "--out", dir.file("e.csv")}).exit_code, 0);
  auto r = conform({"weld-layers", "--eroded", dir.file("e.csv"), "--reference", dir.file("e.reference.csv"),
                    "--bead-spacing", "3", "--layer-height", "1", "--chord-error", "0.05", "--torch-distance", "2",
                    "--out", dir.file("w.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = conform(
      {"export", "--path", dir.file("w.csv"), "--format", "csv", "--approach-mm", "0", "--out", dir.file("wf.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table weld = table(test::read_bytes(dir.file("w.csv")));
  std::vector<std::size_t> all(weld.rows());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  expect_minus_normal(weld, table(test::read_bytes(dir.file("wf.csv"))), all);

  ASSERT_EQ(conform({"generate", "profile", "--out", dir.file("p.csv"), "--seed", "8"}).exit_code, 0);
  r = conform(
      {"profile", "--edge", dir.file("p.csv"), "--features", dir.file("p.features.csv"), "--out", dir.file("cut.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = conform(
      {"export", "--path", dir.file("cut.csv"), "--format", "csv", "--approach-mm", "0", "--out", dir.file("cf.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table cut = table(test::read_bytes(dir.file("cut.csv")));
  std::vector<std::size_t> outline;  // centres (i = -1) are not cut
  for (std::size_t i = 0; i < cut.rows(); ++i) {
    if (number(cut, i, "i") >= 0) outline.push_back(i);
  }
  expect_minus_normal(cut, table(test::read_bytes(dir.file("cf.csv"))), outline);

  // sicp: the generated trajectory (the file sicp reads and writes), z = -n.
  ASSERT_EQ(conform({"generate", "plate", "--out", dir.file("plate.ply")}).exit_code, 0);
  r = conform({"export", "--path", dir.file("plate.trajectory.csv"), "--format", "csv", "--approach-mm", "0", "--out",
               dir.file("sf.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table trajectory = table(test::read_bytes(dir.file("plate.trajectory.csv")));
  std::vector<std::size_t> rows(trajectory.rows());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = i;
  expect_minus_normal(trajectory, table(test::read_bytes(dir.file("sf.csv"))), rows);

  // tube-joint: z = +d of the cut file, and the closed seam ends on its first frame.
  r = conform({"generate", "tube-joint", "--out-leg", dir.file("leg.ply"), "--out-stub", dir.file("stub.ply"),
               "--out-truth", dir.file("truth.csv"), "--edge", "12", "--truth-points", "90", "--pitch-deg", "90",
               "--offset", "0"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = conform({"tube-joint", "--leg", dir.file("leg.ply"), "--stub", dir.file("stub.ply"), "--step-deg", "10",
               "--pitch-deg", "90", "--offset", "0", "--protrusion", "1100", "--groove-deg", "30,45,20,45", "--out-cut",
               dir.file("tc.csv"), "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = conform(
      {"export", "--path", dir.file("tc.csv"), "--format", "csv", "--approach-mm", "0", "--out", dir.file("tf.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table tube = table(test::read_bytes(dir.file("tc.csv")));
  const Table frames = table(test::read_bytes(dir.file("tf.csv")));
  ASSERT_EQ(frames.rows(), tube.rows() + 1);
  for (std::size_t i = 0; i <= tube.rows(); ++i) {
    const std::size_t row = i % tube.rows();
    EXPECT_LT((vec(frames, i, "x_mm", "y_mm", "z_mm") - vec(tube, row, "x_mm", "y_mm", "z_mm")).norm(), 1e-9);
    EXPECT_LT((tool_axis(frames, i) - vec(tube, row, "dx", "dy", "dz").normalized()).norm(), 1e-9) << i;
  }
}

// Two paths in one program (a joint's cut then its weld): the first file's motion points, then the second's, each
// with its own approach and retract, the process lines around each; the same frames as exported one by one.
TEST_F(ExportCommand, SeveralPathFilesGoIntoOneProgramInOrder) {
  ASSERT_EQ(conform({"saddle", "--R", "500", "--r", "120", "--start-pose-deg", "30", "--step-deg", "6", "--out",
                     dir.file("second.csv")})
                .exit_code,
            0);
  for (const auto& [path, out] : {std::pair<std::string, std::string>{"seam.csv", "a.csv"}, {"second.csv", "b.csv"}}) {
    ASSERT_EQ(conform({"export", "--path", dir.file(path), "--format", "csv", "--out", dir.file(out)}).exit_code, 0);
  }
  auto r = conform({"export", "--path", dir.file("seam.csv"), "--path", dir.file("second.csv"), "--format", "csv",
                    "--out", dir.file("ab.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["job"], "saddle");
  EXPECT_EQ(json["segments"], 2);
  ASSERT_EQ(json["paths"].size(), 2u);
  EXPECT_EQ(json["paths"][1]["frames"], 61);
  const Table a = table(test::read_bytes(dir.file("a.csv"))), b = table(test::read_bytes(dir.file("b.csv")));
  const Table ab = table(test::read_bytes(dir.file("ab.csv")));
  ASSERT_EQ(ab.rows(), a.rows() + b.rows());
  for (std::size_t i = 0; i < ab.rows(); ++i) {
    const bool first = i < a.rows();
    const Table& one = first ? a : b;
    const std::size_t k = first ? i : i - a.rows();
    EXPECT_EQ(ab.text(i, ab.column("kind")), one.text(k, one.column("kind"))) << i;
    EXPECT_EQ(number(ab, i, "segment"), first ? 0.0 : 1.0) << i;
    for (const char* c : {"x_mm", "y_mm", "z_mm"}) EXPECT_EQ(number(ab, i, c), number(one, k, c));
    // The same rotation; the quaternion's sign is kept continuous over the whole program, so it may flip.
    double dot = 0.0;
    for (const char* c : {"qw", "qx", "qy", "qz"}) dot += number(ab, i, c) * number(one, k, c);
    EXPECT_NEAR(std::abs(dot), 1.0, 1e-9) << i;  // as written: 12 significant digits
  }
  // A robot program: two approaches and retracts, the process lines around each path.
  r = conform({"export", "--path", dir.file("seam.csv"), "--path", dir.file("second.csv"), "--format", "krl",
               "--process-on", "ARC_ON()", "--process-off", "ARC_OFF()", "--out", dir.file("ab.src")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string krl = test::read_bytes(dir.file("ab.src"));
  std::size_t on = 0, off = 0;
  for (std::size_t at = krl.find("ARC_ON()"); at != std::string::npos; at = krl.find("ARC_ON()", at + 1)) ++on;
  for (std::size_t at = krl.find("ARC_OFF()"); at != std::string::npos; at = krl.find("ARC_OFF()", at + 1)) ++off;
  EXPECT_EQ(on, 2u);
  EXPECT_EQ(off, 2u);
  EXPECT_NE(krl.find("seam.csv, second.csv"), std::string::npos);  // the header names both sources
  // A missing second file: exit 2 naming it, nothing written.
  r = conform({"export", "--path", dir.file("seam.csv"), "--path", dir.file("none.csv"), "--format", "krl", "--out",
               dir.file("x.src")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("none.csv"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("x.src")));
}

TEST_F(ExportCommand, ALargeTurnBetweenFramesIsWarnedAbout) {
  test::write_bytes(dir.file("flip.csv"), "x_mm,y_mm,z_mm,nx,ny,nz\n0,0,0,0,0,1\n1,0,0,0,1,0\n");
  const auto r =
      conform({"export", "--path", dir.file("flip.csv"), "--format", "csv", "--out", dir.file("f.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = nlohmann::json::parse(r.out);
  EXPECT_NEAR(json["max_orientation_step_deg"].get<double>(), 90.0, 1e-9);
  ASSERT_EQ(json["warnings"].size(), 1u);
  EXPECT_NE(r.err.find("wrist flip"), std::string::npos) << r.err;
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
