// The jobs that read CAD besides align and compare, end to end through the `conform` program, each against a result
// known without CAD: fit-cylinder on a STEP cylinder (its radius and axis) and on a coarse generated tube, sicp with
// the nominal surface as STEP (the same trajectory as with the mesh), tube-joint with a STEP leg (the same path as
// with a generated leg mesh), and --cad-save-mesh (the tessellation conform used, written safely and reusable).

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>
#include <nlohmann/json.hpp>

#include "cad_shapes.h"
#include "conform/core/io.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::CadFormat;

test::RunResult conform_run(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

std::vector<double> json_vector(const nlohmann::json& j) { return j.get<std::vector<double>>(); }

// The numbers of a CSV file's rows (the header skipped).
std::vector<std::vector<double>> csv_rows(const std::string& path) {
  std::istringstream in(test::read_bytes(path));
  std::vector<std::vector<double>> rows;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
    rows.push_back(row);
  }
  return rows;
}

// The largest distance between the x, y, z columns (from `first`) of corresponding rows.
double largest_row_distance(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b,
                            std::size_t first) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    const Eigen::Vector3d p(a[i][first], a[i][first + 1], a[i][first + 2]);
    const Eigen::Vector3d q(b[i][first], b[i][first + 1], b[i][first + 2]);
    worst = std::max(worst, (p - q).norm());
  }
  return worst;
}

// A STEP cylinder (R 15, axis z, 40 long): its vertices lie on its rims only, so the default (auto) fits 20,000
// samples of its smooth surface (the caps are outliers): radius within 0.001 mm, axis within 0.01 deg of z through
// the origin.
TEST(CadJobs, FitCylinderFitsTheSurfaceOfAStepCylinder) {
  test::TempDir dir;
  test::write_cad(test::cylinder(), dir.file("cylinder.stp"), CadFormat::kStep, "MM");
  const test::RunResult r = conform_run({"fit-cylinder", "--input", dir.file("cylinder.stp"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["fitted_points"], "surface samples");
  EXPECT_EQ(j["points"], 20000);
  EXPECT_EQ(j["normals"], "surface");
  const std::vector<double> a = json_vector(j["axis_direction"]), c = json_vector(j["axis_point_mm"]);
  const double axis_deg = std::acos(std::min(1.0, std::abs(a[2]))) * 180.0 / M_PI;
  // The axis point's distance from the z axis.
  const double off_axis_mm = std::hypot(c[0] - a[0] * c[2] / a[2], c[1] - a[1] * c[2] / a[2]);
  std::printf("STEP cylinder R 15: radius %.6f mm, axis %.6f deg and %.6f mm off, %.1f %% inliers\n",
              j["radius_mm"].get<double>(), axis_deg, off_axis_mm, 100.0 * j["inlier_fraction"].get<double>());
  EXPECT_NEAR(j["radius_mm"].get<double>(), 15.0, 0.001);
  EXPECT_LT(axis_deg, 0.01);
  EXPECT_LT(off_axis_mm, 0.001);
  EXPECT_NEAR(j["inlier_fraction"].get<double>(), 3770.0 / (3770.0 + 1414.0), 0.02);  // the side's share of the area
  // The vertices, asked for, are refused with a hint.
  const test::RunResult vertices =
      conform_run({"fit-cylinder", "--input", dir.file("cylinder.stp"), "--points", "vertices", "--quiet"});
  EXPECT_EQ(vertices.exit_code, 1);
  EXPECT_NE(vertices.err.find("--points surface"), std::string::npos) << vertices.err;
}

// A coarse generated tube (R 20, 8 mm edges: 0.4 mm chord error), its surface fitted: radius within 0.005 mm.
TEST(CadJobs, FitCylinderFitsTheSurfaceOfACoarseTubeMesh) {
  test::TempDir dir;
  ASSERT_EQ(conform_run({"generate", "tube", "--out", dir.file("tube.ply"), "--radius", "20", "--length", "80",
                         "--edge", "8", "--quiet"})
                .exit_code,
            0);
  const test::RunResult r =
      conform_run({"fit-cylinder", "--input", dir.file("tube.ply"), "--points", "surface", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["fitted_points"], "surface samples");
  const std::vector<double> a = json_vector(j["axis_direction"]);
  std::printf("coarse tube R 20, edge 8 mm, surface: radius %.6f mm, axis %.6f deg off z\n",
              j["radius_mm"].get<double>(), std::acos(std::min(1.0, std::abs(a[2]))) * 180.0 / M_PI);
  EXPECT_NEAR(j["radius_mm"].get<double>(), 20.0, 0.005);
  EXPECT_NEAR(std::abs(a[2]), 1.0, 1e-6);
}

// --cad-save-mesh: the tessellation compare used, written whole; its counts are the reported ones, and compare
// against the saved mesh gives the same deviations. An input as the target, or a format without faces, is exit 2
// and leaves the files as they were.
TEST(CadJobs, SaveMeshWritesTheTessellationUsed) {
  test::TempDir dir;
  const TopoDS_Shape cylinder = test::cylinder();
  test::write_cad(cylinder, dir.file("cylinder.step"), CadFormat::kStep, "MM");
  Mesh scan;
  scan.vertices = test::sample_surface(cylinder, 2000, 0.02, 9).points;
  WriteOptions exact;
  exact.double_precision = true;
  write_mesh(dir.file("scan.ply"), scan, exact);
  // --flat-facets: the tessellation itself on both sides (by default the CAD is measured to its exact faces).
  const test::RunResult r =
      conform_run({"compare", "--scan", dir.file("scan.ply"), "--reference", dir.file("cylinder.step"),
                   "--cad-save-mesh", dir.file("used.ply"), "--flat-facets", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["cad"][0]["saved_mesh"], dir.file("used.ply"));
  const Mesh used = read_mesh(dir.file("used.ply"));
  EXPECT_EQ(used.vertices.size(), j["cad"][0]["vertices"].get<std::size_t>());
  EXPECT_EQ(used.faces.size(), j["cad"][0]["triangles"].get<std::size_t>());
  const test::RunResult again = conform_run(
      {"compare", "--scan", dir.file("scan.ply"), "--reference", dir.file("used.ply"), "--flat-facets", "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const nlohmann::json k = nlohmann::json::parse(again.out);
  for (const char* key : {"mean_mm", "std_mm", "min_mm", "max_mm", "p95_abs_mm"}) {
    EXPECT_NEAR(k[key].get<double>(), j[key].get<double>(), 1e-12) << key;
  }
  const test::RunResult text = conform_run({"info", dir.file("cylinder.step"), "--cad-save-mesh", dir.file("c.stl")});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("wrote        " + dir.file("c.stl")), std::string::npos) << text.out;
  EXPECT_EQ(read_mesh(dir.file("c.stl")).faces.size(), used.faces.size());

  const std::string scan_bytes = test::read_bytes(dir.file("scan.ply"));
  const test::RunResult onto_input = conform_run({"compare", "--scan", dir.file("scan.ply"), "--reference",
                                                  dir.file("cylinder.step"), "--cad-save-mesh", dir.file("scan.ply")});
  EXPECT_EQ(onto_input.exit_code, 2);
  EXPECT_EQ(test::read_bytes(dir.file("scan.ply")), scan_bytes);
  const test::RunResult points = conform_run({"info", dir.file("cylinder.step"), "--cad-save-mesh", dir.file("c.xyz")});
  EXPECT_EQ(points.exit_code, 2);
  EXPECT_NE(points.err.find(".ply, .stl or .obj"), std::string::npos) << points.err;
  test::write_bytes(dir.file("bad.step"), "not step\n");
  EXPECT_EQ(conform_run({"info", dir.file("bad.step"), "--cad-save-mesh", dir.file("never.ply")}).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir.file("never.ply")));
}

// sicp with the plate's nominal surface as STEP (each triangle a planar face, so its tessellation is the same
// triangles) compensates the trajectory exactly as with the nominal mesh.
TEST(CadJobs, SicpSurfaceFromStepGivesTheMeshsTrajectory) {
  test::TempDir dir;
  ASSERT_EQ(conform_run({"generate", "plate", "--out", dir.file("p.ply"), "--scan-points", "8000",
                         "--contour-spacing", "2", "--surface-edge", "20", "--quiet"})
                .exit_code,
            0);
  Mesh nominal = read_mesh(dir.file("p.nominal.ply"));
  nominal.normals.clear();  // the STEP's tessellation has none: the same surface either way
  WriteOptions exact;
  exact.double_precision = true;
  write_mesh(dir.file("nominal.ply"), nominal, exact);
  std::vector<std::array<std::int32_t, 3>> triangles(nominal.faces.begin(), nominal.faces.end());
  test::write_cad(test::faces_of_triangles(nominal.vertices, triangles), dir.file("nominal.step"), CadFormat::kStep,
                  "MM");
  const auto sicp = [&](const std::string& surface, const std::string& out) {
    return conform_run({"sicp", "--contour", dir.file("p.contour.csv"), "--scan", dir.file("p.ply"), "--trajectory",
                        dir.file("p.trajectory.csv"), "--surface", surface, "--out-trajectory", out, "--json",
                        "--quiet"});
  };
  const test::RunResult mesh = sicp(dir.file("nominal.ply"), dir.file("mesh.csv"));
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const test::RunResult step = sicp(dir.file("nominal.step"), dir.file("step.csv"));
  ASSERT_EQ(step.exit_code, 0) << step.err;
  const nlohmann::json j = nlohmann::json::parse(step.out);
  EXPECT_EQ(j["cad"][0]["triangles"].get<std::size_t>(), nominal.faces.size());
  const double worst = largest_row_distance(csv_rows(dir.file("mesh.csv")), csv_rows(dir.file("step.csv")), 0);
  std::printf("sicp, nominal surface as mesh and as STEP (%zu faces): trajectories differ by at most %.3g mm\n",
              nominal.faces.size(), worst);
  EXPECT_LT(worst, 1e-4);
}

// tube-joint with the leg as a STEP cylinder (R 300 along z_L) and the generated stub: the same intersection path as
// with the generated leg mesh of that cylinder (10 mm edges: chords up to 0.042 mm inside), within 0.1 mm.
TEST(CadJobs, TubeJointWithAStepLegGivesTheMeshsPath) {
  test::TempDir dir;
  const test::RunResult g = conform_run({"generate", "tube-joint", "--out-leg", dir.file("leg.ply"), "--out-stub",
                                         dir.file("stub.ply"), "--out-truth", dir.file("truth.csv"), "--leg-radius",
                                         "300", "--stub-radius", "160",
                                         "--wall", "10", "--edge", "10", "--pitch-deg", "60", "--offset", "30",
                                         "--json"});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  std::ostringstream protrusion;
  protrusion.precision(17);
  protrusion << nlohmann::json::parse(g.out)["protrusion_mm"].get<double>();
  test::write_cad(test::cylinder(300.0, -700.0, 700.0), dir.file("leg.step"), CadFormat::kStep, "MM");
  const auto joint = [&](const std::string& leg, const std::string& out) {
    return conform_run({"tube-joint", "--leg", leg, "--stub", dir.file("stub.ply"), "--pitch-deg", "60", "--offset",
                        "30", "--protrusion", protrusion.str(), "--step-deg", "5", "--out-path", out, "--json"});
  };
  const test::RunResult mesh = joint(dir.file("leg.ply"), dir.file("mesh.csv"));
  ASSERT_EQ(mesh.exit_code, 0) << mesh.err;
  const test::RunResult step = joint(dir.file("leg.step"), dir.file("step.csv"));
  ASSERT_EQ(step.exit_code, 0) << step.err;
  EXPECT_EQ(nlohmann::json::parse(step.out)["cad"].size(), 1u);
  const double worst = largest_row_distance(csv_rows(dir.file("mesh.csv")), csv_rows(dir.file("step.csv")), 1);
  std::printf("tube-joint, leg as mesh and as STEP: paths differ by at most %.4f mm\n", worst);
  EXPECT_LT(worst, 0.1);
}

}  // namespace
}  // namespace conform
