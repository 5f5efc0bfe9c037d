// `conform tube-joint` end to end on a generated pair: the CSVs and their headers, --json, the same bytes on a
// rerun, exit 1 (no closed curve, no file) and exit 2 (bad input, naming it).

#include <algorithm>
#include <cstdio>
#include <fstream>
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

// User errors are bad input (exit 2, no file), not geometry: a missing or negative protrusion, meshes in metres,
// negative angles, impossible groove tables.
TEST(TubeJointCommand, UserErrorsAreExitTwoNotGeometry) {
  const Pair& pair = shared_pair();
  const test::TempDir out;
  const auto expect_two = [&](std::vector<std::string> args, const std::string& says) {
    args.insert(args.end(), {"--out-path", out.file("path.csv")});
    const test::RunResult r = test::run(CONFORM_EXE, args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(out.listing(), "");
  };
  auto args = pair.args();
  expect_two(std::vector<std::string>(args.begin(), args.end() - 2), "--protrusion");
  args.back() = "-900";
  expect_two(args, "protrusion");
  args = pair.args();
  args.insert(args.end(), {"--weld-angle-deg", "-30"});
  expect_two(args, "weld angle");
  args = pair.args();
  args.insert(args.end(), {"--groove-deg", "30,-5,20,45"});
  expect_two(args, "groove angle");
  test::write_bytes(out.file("groove.csv"), "phi_deg,alpha_deg\n0,30\n90,45\n360,20\n");
  args = pair.args();
  args.insert(args.end(), {"--groove-table", out.file("groove.csv")});
  const test::RunResult table = test::run(CONFORM_EXE, args);
  EXPECT_EQ(table.exit_code, 2);
  EXPECT_NE(table.err.find("groove.csv"), std::string::npos) << table.err;
  std::remove(out.file("groove.csv").c_str());
  for (const char* name : {"leg.ply", "stub.ply"}) {
    Mesh mesh = read_mesh(pair.dir.file(name));
    for (Eigen::Vector3d& v : mesh.vertices) v *= 0.001;
    write_mesh(out.file(std::string("m_") + name), mesh);
  }
  args = pair.args();
  args[2] = out.file("m_leg.ply");
  args[4] = out.file("m_stub.ply");
  args.insert(args.end(), {"--out-path", out.file("path.csv")});
  const test::RunResult metres = test::run(CONFORM_EXE, args);
  EXPECT_EQ(metres.exit_code, 2) << metres.err;
  EXPECT_NE(metres.err.find("metres"), std::string::npos) << metres.err;
}

// A groove table and its periodic spline; alpha and psi in the tool files.
TEST(TubeJointCommand, GrooveTableAndTheAnglesInTheToolFiles) {
  const Pair& pair = shared_pair();
  const test::TempDir out;
  test::write_bytes(out.file("groove.csv"), "phi_deg,alpha_deg\n0,30\n60,35\n150,25\n240,35\n360,30\n");
  auto args = pair.args();
  args.insert(args.end(), {"--groove-table", out.file("groove.csv"), "--groove-interpolation", "spline",
                           "--step-deg", "30", "--weld-angle-deg", "10", "--out-cut", out.file("cut.csv"), "--out-weld",
                           out.file("weld.csv")});
  const test::RunResult r = test::run(CONFORM_EXE, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream cut(test::read_bytes(out.file("cut.csv")));
  std::string line;
  std::getline(cut, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(cut, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  ASSERT_EQ(rows.size(), 12u);
  const double deg = 3.141592653589793 / 180.0;
  EXPECT_NEAR(rows[0][7], 30 * deg, 1e-9);  // the spline passes through the rows
  EXPECT_NEAR(rows[2][7], 35 * deg, 1e-9);
  EXPECT_NEAR(rows[5][7], 25 * deg, 1e-9);
  for (const auto& row : rows) {
    EXPECT_GT(row[8], row[7]);  // psi above the groove angle: the cut leaves the wall through its outer surface
    EXPECT_LT(row[8], 3.141592653589793);
  }
  // pitch 60: the dihedral at the toe is 180 - 60 = 120 deg, at the heel 60 deg (within the ovality's few degrees).
  EXPECT_NEAR(rows[0][8], 120 * deg, 4 * deg);
  EXPECT_NEAR(rows[6][8], 60 * deg, 4 * deg);
  EXPECT_NE(test::read_bytes(out.file("weld.csv")).find(",0.174532925,"), std::string::npos);  // alpha_w = 10 deg
}

// The docs' example, end to end: the weld torch at 40 deg with grooves down to 20 deg stands inside the 25 mm stub
// wall wherever the groove is below 40 deg (264 of 360 points), so it is refused (exit 1, no file); at 10 deg
// (below every groove angle) no tool tip or approach line is inside material.
TEST(TubeJointCommandMatrix, TheDocsExampleHasNoToolInsideMaterial) {
  const test::TempDir dir;
  const test::RunResult g = test::run(
      CONFORM_EXE, {"generate", "tube-joint", "--out-leg", dir.file("leg.ply"), "--out-stub", dir.file("stub.ply"),
                    "--out-truth", dir.file("truth.csv"), "--pitch-deg", "45", "--offset", "100", "--ovality-pct", "1",
                    "--peaking", "3", "--leg-bump=-10,150,2,80", "--stub-bump", "200,300,2,60", "--noise", "0.2"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  std::vector<std::string> args = {"tube-joint", "--leg", dir.file("leg.ply"), "--stub", dir.file("stub.ply"),
                                   "--pitch-deg", "45", "--offset", "100", "--protrusion", "2014.2135623730949",
                                   "--step-deg", "1", "--groove-deg", "30,45,20,45", "--weld-standoff", "15",
                                   "--wall-thickness", "25", "--out-weld", dir.file("weld.csv"), "--json",
                                   "--weld-angle-deg", "40"};
  const test::RunResult unsafe = test::run(CONFORM_EXE, args);
  EXPECT_EQ(unsafe.exit_code, 1) << unsafe.err;
  const nlohmann::json u = nlohmann::json::parse(unsafe.out);
  EXPECT_EQ(u["condition"], "safety");
  // The 1-deg azimuths where alpha_c(phi) < 40 deg (264); at the two where it is 40 deg within the normals' noise
  // (phi = +-60 deg) the tip lies on the wall's face and goes either way.
  EXPECT_NEAR(u["safety"]["weld_tip_in_stub"]["count"].get<double>(), 264.0, 2.0);
  EXPECT_NE(unsafe.err.find("inside the stub wall"), std::string::npos) << unsafe.err;
  EXPECT_FALSE(std::ifstream(dir.file("weld.csv")).good());
  args.back() = "10";
  const test::RunResult safe = test::run(CONFORM_EXE, args);
  ASSERT_EQ(safe.exit_code, 0) << safe.err;
  const nlohmann::json j = nlohmann::json::parse(safe.out);
  EXPECT_EQ(j["safety"]["ok"], true);
  EXPECT_EQ(j["safety"]["walls_checked"], true);
  for (const char* kind : {"groove_beyond_wall", "cut_tip_in_stub", "cut_line_in_stub", "weld_tip_in_stub",
                           "weld_tip_in_leg", "weld_line_in_material"}) {
    EXPECT_EQ(j["safety"][kind]["count"], 0) << kind;
  }
}

}  // namespace
}  // namespace conform
