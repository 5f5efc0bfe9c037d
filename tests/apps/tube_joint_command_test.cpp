// `conform tube-joint` end to end on a generated pair: the CSVs and their headers, --json, the same bytes on a
// rerun, exit 1 (no closed curve, no file) and exit 2 (bad input, naming it).

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include "conform/core/io.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

struct Pair {
  test::TempDir dir;
  std::string protrusion;
  Pair() {
    const test::RunResult r = test::run(CONFORM_EXE, {"generate",       "tube-joint",
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
                                                      "--noise",        "0.2",
                                                      "--json"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ostringstream text;
    text.precision(17);
    text << nlohmann::json::parse(r.out)["protrusion_mm"].get<double>();
    protrusion = text.str();
  }
  std::vector<std::string> args() const {
    return {"tube-joint", "--leg", dir.file("leg.ply"), "--stub",  dir.file("stub.ply"), "--pitch-deg", "60",
            "--offset",   "30",    "--protrusion",      protrusion};
  }
};

// One generated pair for the whole suite (generation is the slow part).
const Pair& shared_pair() {
  static const Pair pair;
  return pair;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

TEST(TubeJointCommand, WritesPathCutAndWeldWithTheIssuesHeadersAndSameBytesOnARerun) {
  const Pair& pair = shared_pair();
  const test::TempDir out;
  auto args = pair.args();
  args.insert(args.end(), {"--step-deg", "2", "--groove-deg", "30,45,20,45", "--out-path", out.file("path.csv"),
                           "--out-cut", out.file("cut.csv"), "--out-weld", out.file("weld.csv"), "--json"});
  const test::RunResult r = test::run(CONFORM_EXE, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], 180);
  EXPECT_EQ(j["closed"], true);
  EXPECT_GT(j["path_length_mm"].get<double>(), 900.0);
  EXPECT_GT(j["max_step_mm"].get<double>(), j["min_step_mm"].get<double>());
  const std::string path = test::read_bytes(out.file("path.csv"));
  EXPECT_EQ(first_line(path), "phi_rad,x_mm,y_mm,z_mm,tx,ty,tz,nsx,nsy,nsz,nlx,nly,nlz");
  EXPECT_EQ(first_line(test::read_bytes(out.file("cut.csv"))), "phi_rad,x_mm,y_mm,z_mm,dx,dy,dz,alpha_rad,psi_rad");
  EXPECT_EQ(first_line(test::read_bytes(out.file("weld.csv"))), "phi_rad,x_mm,y_mm,z_mm,dx,dy,dz,alpha_rad,psi_rad");
  EXPECT_EQ(std::count(path.begin(), path.end(), '\n'), 181);
  ASSERT_EQ(test::run(CONFORM_EXE, args).exit_code, 0);
  EXPECT_EQ(test::read_bytes(out.file("path.csv")), path);
}

TEST(TubeJointCommand, ArcLengthStepsAndTextOutput) {
  const Pair& pair = shared_pair();
  auto args = pair.args();
  args.insert(args.end(), {"--step-mm", "10"});
  const test::RunResult r = test::run(CONFORM_EXE, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("closed, one turn"), std::string::npos) << r.out;
}

TEST(TubeJointCommand, AJointThatDoesNotMeetIsExitOneWithTheConditionAndNoFile) {
  const Pair& pair = shared_pair();
  const test::TempDir out;
  auto args = pair.args();
  args.back() = "3000";  // protrusion: the leg posed far beyond the stub
  args.insert(args.end(), {"--out-path", out.file("path.csv"), "--json"});
  const test::RunResult r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["closed"], false);
  EXPECT_EQ(j["condition"], "intersect");
  EXPECT_NE(r.err.find("[intersect]"), std::string::npos) << r.err;
  EXPECT_EQ(out.listing(), "");
}

// The stub scanned somewhere else (moved by a rigid transform), with 4 markers: its frame comes back from the
// cylinder fit + markers, and the path matches the one computed on the stub in its frame.
TEST(TubeJointCommand, StubMarkersEstablishTheStubFrame) {
  const Pair& pair = shared_pair();
  const test::TempDir out;
  const Mesh stub = read_mesh(pair.dir.file("stub.ply"));
  const Eigen::Isometry3d T =
      Eigen::Translation3d(250.0, -80.0, 40.0) * Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, 1.0, 0.2).normalized());
  Mesh moved = stub;
  for (Eigen::Vector3d& v : moved.vertices) v = T * v;
  write_mesh(out.file("moved.ply"), moved);
  std::string csv = "x_mm,y_mm,z_mm,ref_x_mm,ref_y_mm,ref_z_mm\n";
  const std::size_t n = stub.vertices.size();
  ASSERT_GT(n, 100u);
  for (const std::size_t i : {n / 50, n / 3, n / 2 + 7, n - 20}) {  // spread round and along the stub
    const Eigen::Vector3d& v = stub.vertices[i];
    const Eigen::Vector3d m = T * v;
    std::ostringstream row;
    row.precision(12);
    row << m.x() << "," << m.y() << "," << m.z() << "," << v.x() << "," << v.y() << "," << v.z() << "\n";
    csv += row.str();
  }
  test::write_bytes(out.file("markers.csv"), csv);
  auto args = pair.args();
  args.insert(args.end(), {"--step-deg", "5", "--json"});
  const test::RunResult direct = test::run(CONFORM_EXE, args);
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  args[4] = out.file("moved.ply");
  args.insert(args.end(), {"--stub-markers", out.file("markers.csv")});
  const test::RunResult via_markers = test::run(CONFORM_EXE, args);
  ASSERT_EQ(via_markers.exit_code, 0) << via_markers.err;
  const nlohmann::json a = nlohmann::json::parse(direct.out);
  const nlohmann::json b = nlohmann::json::parse(via_markers.out);
  ASSERT_EQ(b["stub_marker_residuals_mm"].size(), 4u);
  // The fit of a 1%-oval, 0.2 mm-noise stub puts the markers within a millimetre; the path length follows.
  for (const auto& d : b["stub_marker_residuals_mm"]) EXPECT_LT(d.get<double>(), 1.0);
  EXPECT_NEAR(a["path_length_mm"].get<double>(), b["path_length_mm"].get<double>(), 2.0);
  // Two markers are not enough.
  const std::string two = csv.substr(0, csv.find('\n', csv.find('\n', csv.find('\n') + 1) + 1) + 1);
  test::write_bytes(out.file("two.csv"), two);
  args.back() = out.file("two.csv");
  const test::RunResult r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("two.csv"), std::string::npos) << r.err;
}

TEST(TubeJointCommand, BadInputIsExitTwoNamingIt) {
  const Pair& pair = shared_pair();
  const test::TempDir out;
  test::RunResult r =
      test::run(CONFORM_EXE, {"tube-joint", "--leg", out.file("missing.ply"), "--stub", pair.dir.file("stub.ply"),
                              "--pitch-deg", "60", "--offset", "0", "--protrusion", "900"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.ply"), std::string::npos) << r.err;
  auto args = pair.args();
  args.insert(args.end(), {"--groove-deg", "30,45"});
  r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--groove-deg"), std::string::npos) << r.err;
  args = pair.args();
  args[6] = "120";  // pitch
  r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("pitch"), std::string::npos) << r.err;
  r = test::run(CONFORM_EXE, {"tube-joint", "--leg", pair.dir.file("leg.ply"), "--stub", pair.dir.file("stub.ply")});
  EXPECT_EQ(r.exit_code, 2);
  args = pair.args();
  args.insert(args.end(), {"--out-path", out.file("path.txt")});
  r = test::run(CONFORM_EXE, args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("path.txt"), std::string::npos) << r.err;
  EXPECT_EQ(out.listing(), "");
}

}  // namespace
}  // namespace conform
