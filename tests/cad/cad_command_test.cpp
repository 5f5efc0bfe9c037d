// STEP and IGES references end to end through the `conform` program: info, align, compare, fit-cylinder, the exit
// code of bad CAD, and a start-up that does not load OpenCASCADE.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <TopoDS_Shape.hxx>
#include <nlohmann/json.hpp>

#include "cad_shapes.h"
#include "conform/core/cloud.h"
#include "conform/core/io.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::CadFormat;

test::RunResult conform_run(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

// The scan as a .ply cloud, its points moved by T_scan_ref.
void write_scan(const test::SurfaceSample& sample, const Eigen::Isometry3d& T_scan_ref, const std::string& path) {
  Mesh cloud;
  for (const Eigen::Vector3d& p : sample.points) cloud.vertices.push_back(T_scan_ref * p);
  WriteOptions options;
  options.double_precision = true;
  write_mesh(path, cloud, options);
}

TEST(CadCommand, InfoListsBodiesUnitsAndTessellation) {
  test::TempDir dir;
  test::write_cad(test::box_with_boss_and_hole(), dir.file("box.step"), CadFormat::kStep, "M");
  const test::RunResult text = conform_run({"info", dir.file("box.step")});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("cad unit     metre (x1000 to mm)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("body 1       solid, 12 faces"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("deflection 0.005 mm"), std::string::npos) << text.out;
  const test::RunResult json = conform_run({"info", dir.file("box.step"), "--json", "--cad-deflection", "0.01"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["cad"]["file_unit"], "metre");
  EXPECT_EQ(j["cad"]["deflection_mm"], 0.01);
  EXPECT_EQ(j["cad"]["bodies"].size(), 1u);
  EXPECT_EQ(j["cad"]["triangles"], j["faces"]);
  EXPECT_NEAR(j["bounding_box_max_mm"][2].get<double>(), 30.0, 1e-9);
}

TEST(CadCommand, AlignsAScanToAStepReference) {
  test::TempDir dir;
  const TopoDS_Shape box = test::box_with_boss_and_hole();
  test::write_cad(box, dir.file("box.step"), CadFormat::kStep, "MM");
  Eigen::Isometry3d T_ref_scan = Eigen::Isometry3d::Identity();
  T_ref_scan.rotate(Eigen::AngleAxisd(1.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()));
  T_ref_scan.translation() = Eigen::Vector3d(0.6, -0.4, 0.3);
  write_scan(test::sample_surface(box, 20000, 0.02, 11), T_ref_scan.inverse(), dir.file("scan.ply"));
  const test::RunResult r =
      conform_run({"align", "--scan", dir.file("scan.ply"), "--reference", dir.file("box.step"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) T(row, col) = j["T_ref_scan"][row][col].get<double>();
  }
  const Eigen::Isometry3d error(T_ref_scan.inverse().matrix() * T);
  const double rotation_deg = Eigen::AngleAxisd(error.rotation()).angle() * 180.0 / M_PI;
  // The translation error where it matters: at the part (its centre, 30 20 12 mm).
  const double translation_mm = (error * Eigen::Vector3d(30, 20, 12) - Eigen::Vector3d(30, 20, 12)).norm();
  EXPECT_LT(rotation_deg, 0.005);
  EXPECT_LT(translation_mm, 0.01);
  std::printf("align against STEP: rotation error %.5f deg, translation error at the part %.5f mm\n", rotation_deg,
              translation_mm);
  ASSERT_EQ(j["cad"].size(), 1u);
  EXPECT_EQ(j["cad"][0]["triangles"], j["reference_faces"]);
  EXPECT_EQ(j["cad"][0]["deflection_mm"], 0.005);
}

TEST(CadCommand, CompareAgainstIgesInMetresGivesTheNoise) {
  test::TempDir dir;
  const TopoDS_Shape cylinder = test::cylinder();
  test::write_cad(cylinder, dir.file("cylinder.igs"), CadFormat::kIges, "M");
  const test::SurfaceSample scan = test::sample_surface(cylinder, 4000, 0.03, 5);
  write_scan(scan, Eigen::Isometry3d::Identity(), dir.file("scan.ply"));
  // At the default deflection (0.005 mm): compare measures to the exact faces, so the chords' offset (a third of
  // the deflection) does not show and the mean is the noise's to 1e-4 mm; with --flat-facets it does.
  const test::RunResult r =
      conform_run({"compare", "--scan", dir.file("scan.ply"), "--reference", dir.file("cylinder.igs"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  double mean = 0.0, sq = 0.0;
  for (double d : scan.offset_mm) mean += d;
  mean /= static_cast<double>(scan.offset_mm.size());
  for (double d : scan.offset_mm) sq += (d - mean) * (d - mean);
  const double std_mm = std::sqrt(sq / static_cast<double>(scan.offset_mm.size()));
  EXPECT_NEAR(j["mean_mm"].get<double>(), mean, 1e-4) << r.out;
  EXPECT_NEAR(j["std_mm"].get<double>(), std_mm, 0.001) << r.out;
  EXPECT_EQ(j["surface"], "exact CAD faces");
  EXPECT_EQ(j["cad"][0]["deflection_mm"], 0.005);
  const test::RunResult flat = conform_run({"compare", "--scan", dir.file("scan.ply"), "--reference",
                                            dir.file("cylinder.igs"), "--json", "--flat-facets"});
  ASSERT_EQ(flat.exit_code, 0) << flat.err;
  const nlohmann::json f = nlohmann::json::parse(flat.out);
  EXPECT_EQ(f["surface"], "flat facets");
  EXPECT_GT(f["mean_mm"].get<double>() - j["mean_mm"].get<double>(), 0.0008);  // chords inside the curved side
  std::printf("compare against the IGES cylinder at 0.005 mm: mean %.5f (exact), %.5f (flat facets), noise %.5f mm\n",
              j["mean_mm"].get<double>(), f["mean_mm"].get<double>(), mean);
  EXPECT_EQ(j["cad"][0]["file_unit"], "M");
  EXPECT_EQ(j["cad"][0]["mm_per_file_unit"], 1000.0);
  const test::RunResult text =
      conform_run({"compare", "--scan", dir.file("scan.ply"), "--reference", dir.file("cylinder.igs")});
  EXPECT_NE(text.out.find("IGES in M (x1000 to mm)"), std::string::npos) << text.out;
  // A scan in metres: --units m scales the scan, not the CAD (its unit is its own), and says so.
  Eigen::Isometry3d to_metres = Eigen::Isometry3d::Identity();
  to_metres.linear() *= 0.001;
  write_scan(scan, to_metres, dir.file("scan_m.ply"));
  const test::RunResult metres = conform_run({"compare", "--scan", dir.file("scan_m.ply"), "--reference",
                                              dir.file("cylinder.igs"), "--units", "m", "--json"});
  ASSERT_EQ(metres.exit_code, 0) << metres.err;
  EXPECT_NEAR(nlohmann::json::parse(metres.out)["std_mm"].get<double>(), std_mm, 0.002);
  EXPECT_NE(metres.err.find("does not apply to a CAD file"), std::string::npos) << metres.err;
}

// fit-cylinder reads a STEP input and reports it (its fit: CadJobs.FitCylinderFitsTheSurfaceOfAStepCylinder).
TEST(CadCommand, FitCylinderReadsStep) {
  test::TempDir dir;
  test::write_cad(test::cylinder(), dir.file("cylinder.stp"), CadFormat::kStep, "MM");
  const test::RunResult r = conform_run({"fit-cylinder", "--input", dir.file("cylinder.stp"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["cad"].size(), 1u);
  EXPECT_EQ(j["cad"][0]["faces"], 3u);
  EXPECT_GT(j["cad"][0]["triangles"].get<int>(), 100);
}

TEST(CadCommand, BadCadIsExitTwoNamingTheFile) {
  test::TempDir dir;
  test::write_bytes(dir.file("part.step"), "not step at all\n");
  const test::RunResult r = conform_run({"info", dir.file("part.step")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dir.file("part.step") + ": not a STEP file"), std::string::npos) << r.err;
  test::write_cad(test::cylinder(), dir.file("ok.step"), CadFormat::kStep, "MM");
  const test::RunResult d = conform_run({"info", dir.file("ok.step"), "--cad-deflection", "-1"});
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("deflection"), std::string::npos) << d.err;
}

// DESIGN.md: cad/ is kept out of the start-up path.
TEST(CadCommand, HelpDoesNotLoadOpenCascade) {
  const test::RunResult r = test::run("/usr/bin/env", {"LD_DEBUG=libs", CONFORM_EXE, "--help"});
  ASSERT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("libc.so"), std::string::npos) << "LD_DEBUG gave no trace";
  EXPECT_EQ(r.err.find("libTKernel"), std::string::npos);
  EXPECT_EQ(r.err.find("libconform_cad"), std::string::npos);
}

}  // namespace
}  // namespace conform
