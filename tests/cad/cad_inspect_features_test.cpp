// `conform inspect`'s holes as features: a hole the CAD splits into two half-cylinder faces is one feature, measured
// on the points of both; its diameter and position judged by the tolerance file's diameter_lower_mm,
// diameter_upper_mm and position_mm. The part: an 80 x 60 x 20 mm block (OpenCASCADE, STEP) with hole A (R 6, split,
// made 0.05 mm oversize in radius and moved (0.03, 0.08) mm), hole B (R 6, one face, moved 0.1 mm in x) and hole C
// (R 4, split, made right). The scan: noise 0.005 mm, the hole walls seen over a 240-degree arc only, the bottom and
// the side y = 0 not at all, stray points above the part; three seeds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>
#include <nlohmann/json.hpp>

#include "cad_shapes.h"
#include "conform/core/cad_faces.h"
#include "conform/core/random.h"
#include "conform/pipelines/inspect/inspect.h"
#include "conform/pipelines/inspect/inspect_json.h"
#include "conform/pipelines/inspect/inspect_report.h"
#include "report_page_checks.h"
#include "inspect_scans.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

constexpr double kNoise = 0.005;

const test::MadeHole kHoleA{{20.0, 30.0}, 6.0, 0.05, {0.03, 0.08}};
const test::MadeHole kHoleB{{60.0, 30.0}, 6.0, 0.0, {0.1, 0.0}};
const test::MadeHole kHoleC{{40.0, 12.0}, 4.0, 0.0, {0.0, 0.0}};

TopoDS_Shape block_with_three_holes() {
  TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 80.0, 60.0, 20.0).Shape();
  part = test::drill_split_hole(part, 20.0, 30.0, 6.0, -5.0, 25.0);
  part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(60, 30, -5), gp::DZ()), 6.0, 30.0).Shape())
             .Shape();
  return test::drill_split_hole(part, 40.0, 12.0, 4.0, -5.0, 25.0);
}

// The hole a cylindrical face belongs to, by its nominal axis.
const test::MadeHole& hole_of(const CadFace& f) {
  for (const test::MadeHole* h : {&kHoleA, &kHoleB, &kHoleC}) {
    if ((f.origin_mm.head<2>() - h->centre).norm() < 1e-6) return *h;
  }
  throw std::runtime_error("a cylinder face on no hole");
}

struct Part {
  std::string step;
  CadFaces cad;
};

// Noise, the walls of the holes seen over 240 degrees (not where the radial direction points within 60 degrees of
// (-1, -1)/sqrt 2), no bottom, no side y = 0, 200 stray points 3-8 mm above the top.
std::vector<Eigen::Vector3d> scan_of(const TopoDS_Shape& shape, const CadFaces& cad, std::uint64_t seed) {
  const test::SurfaceSample s = test::sample_surface(shape, 40000, 0.0, seed);
  Random random(seed + 100);
  const Eigen::Vector2d unseen = Eigen::Vector2d(-1.0, -1.0).normalized();
  std::vector<Eigen::Vector3d> out;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const CadFace& f = cad.faces[static_cast<std::size_t>(s.face[i])];
    double error = 0.0;
    if (f.type == CadSurfaceType::kCylinder) {
      const test::MadeHole& hole = hole_of(f);
      if ((s.points[i].head<2>() - hole.centre).normalized().dot(unseen) > 0.5) continue;
      error = test::hole_error(hole, s.points[i]);
    } else if (f.axis.z() < -0.5 || f.axis.y() < -0.5) {
      continue;
    }
    out.push_back(s.points[i] + (error + kNoise * random.normal()) * s.normals[i]);
  }
  for (int i = 0; i < 200; ++i) {
    const double x = random.uniform(5.0, 75.0), y = random.uniform(5.0, 55.0), z = random.uniform(23.0, 28.0);
    out.emplace_back(x, y, z);
  }
  return out;
}

// The feature whose faces include face id `face`.
const FeatureInspection& feature_with(const InspectResult& r, std::size_t face) {
  for (const FeatureInspection& f : r.features) {
    if (std::find(f.faces.begin(), f.faces.end(), face) != f.faces.end()) return f;
  }
  throw std::runtime_error("no feature holds face " + std::to_string(face));
}

TEST(InspectFeatures, ASplitHoleIsOneFeatureWithItsSizeAndPosition) {
  test::TempDir dir;
  const TopoDS_Shape shape = block_with_three_holes();
  const std::string step = dir.file("part.step");
  const CadFaces cad = test::write_step(shape, step);
  // The CAD as made: 6 planes, holes A and C two faces each, B one.
  std::vector<std::size_t> faces_a, faces_b, faces_c;
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    if (cad.faces[f].type != CadSurfaceType::kCylinder) continue;
    const test::MadeHole& h = hole_of(cad.faces[f]);
    (&h == &kHoleA ? faces_a : &h == &kHoleB ? faces_b : faces_c).push_back(f + 1);
  }
  ASSERT_EQ(faces_a.size(), 2u);
  ASSERT_EQ(faces_b.size(), 1u);
  ASSERT_EQ(faces_c.size(), 2u);
  ASSERT_EQ(cad.faces.size(), 11u);

  // A: size fails (12.1 over 12.05), position passes (0.171 under 0.2); B: size passes, position fails (0.2 over
  // 0.1); C passes both. The limits are named by one face of each hole; the second of A's carries a profile limit.
  test::write_bytes(dir.file("limits.csv"),
                    "face,lower_mm,upper_mm,diameter_lower_mm,diameter_upper_mm,position_mm\n" +
                        std::to_string(faces_a[0]) + ",,,11.95,12.05,0.2\n" + std::to_string(faces_a[1]) +
                        ",-0.2,0.2,,,\n" + std::to_string(faces_b[0]) + ",,,11.95,12.05,0.1\n" +
                        std::to_string(faces_c[1]) + ",,,7.95,8.05,0.05\n");
  for (const std::uint64_t seed : {3u, 17u, 41u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    test::write_scan(dir.file("scan.ply"), scan_of(shape, cad, seed));
    InspectOptions options;
    options.scan_path = dir.file("scan.ply");
    options.reference_path = step;
    options.tolerances_path = dir.file("limits.csv");
    const InspectResult r = run_inspect(options);
    ASSERT_TRUE(r.ok) << r.termination;
    ASSERT_EQ(r.features.size(), 3u);  // not five: a split hole is one feature
    const FeatureInspection& a = feature_with(r, faces_a[0]);
    const FeatureInspection& b = feature_with(r, faces_b[0]);
    const FeatureInspection& c = feature_with(r, faces_c[0]);
    EXPECT_EQ(a.faces, faces_a);
    EXPECT_EQ(c.faces, faces_c);
    // The feature is measured on the points of all its faces.
    EXPECT_EQ(a.measured.points, r.faces[faces_a[0] - 1].points + r.faces[faces_a[1] - 1].points);
    EXPECT_GT(r.faces[faces_a[0] - 1].points, 300u);
    EXPECT_GT(r.faces[faces_a[1] - 1].points, 300u);
    for (const FeatureInspection* f : {&a, &b, &c}) {
      ASSERT_TRUE(f->measured.fitted) << f->measured.fit_note;
      EXPECT_LT(f->measured.form.width_mm, 7.0 * kNoise);  // size and position are not form
      EXPECT_EQ(f->measured.nominal.sense, -1);            // a hole
    }
    EXPECT_NEAR(2.0 * a.measured.radius_mm, 12.1, 0.004);
    EXPECT_NEAR(a.measured.axis_point_mm.x(), 20.03, 0.003);
    EXPECT_NEAR(a.measured.axis_point_mm.y(), 30.08, 0.003);
    EXPECT_NEAR(a.measured.position_mm, 2.0 * kHoleA.shift_mm.norm(), 0.006);
    EXPECT_NEAR(2.0 * b.measured.radius_mm, 12.0, 0.004);
    EXPECT_NEAR(b.measured.position_mm, 0.2, 0.006);
    EXPECT_NEAR(2.0 * c.measured.radius_mm, 8.0, 0.004);
    EXPECT_LT(c.measured.position_mm, 0.008);
    // The verdicts.
    ASSERT_TRUE(a.verdict && b.verdict && c.verdict);
    EXPECT_TRUE(a.verdict->measured);
    EXPECT_FALSE(a.verdict->size_pass);
    EXPECT_TRUE(a.verdict->position_pass);
    EXPECT_TRUE(b.verdict->size_pass);
    EXPECT_FALSE(b.verdict->position_pass);
    EXPECT_FALSE(b.verdict->pass);
    EXPECT_TRUE(c.verdict->pass);
    EXPECT_EQ(r.verdict, "fail");
    // A's second face keeps its own profile limit, A's first face none (its row limits the feature only).
    EXPECT_TRUE(r.faces[faces_a[1] - 1].verdict.has_value());
    EXPECT_FALSE(r.faces[faces_a[0] - 1].verdict.has_value());
  }

  // The CLI: the `features` array, its verdicts, the exit code 0 with the verdict in the output.
  const test::RunResult run = test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step,
                                                      "--tolerances", dir.file("limits.csv"), "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  ASSERT_EQ(j.at("features").size(), 3u);
  // Features in the order of their first faces: C (its faces come first in the file), A, B.
  ASSERT_LT(faces_c[0], faces_a[0]);
  ASSERT_LT(faces_a[0], faces_b[0]);
  const nlohmann::json& ja = j.at("features")[1];
  EXPECT_EQ(ja.at("id"), 2);
  EXPECT_EQ(ja.at("kind"), "hole");
  EXPECT_EQ(ja.at("faces").get<std::vector<std::size_t>>(), faces_a);
  EXPECT_EQ(ja.at("nominal_diameter_mm").get<double>(), 12.0);
  EXPECT_NEAR(ja.at("diameter_mm").get<double>(), 12.1, 0.004);
  EXPECT_EQ(ja.at("tolerance").at("size_pass"), false);
  EXPECT_EQ(ja.at("tolerance").at("position_pass"), true);
  EXPECT_EQ(j.at("verdict"), "fail");
  // The report (in process, as --report builds it): a table of the holes, every cell tied to the JSON's features.
  InspectOptions options;
  options.scan_path = dir.file("scan.ply");
  options.reference_path = step;
  options.tolerances_path = dir.file("limits.csv");
  options.keep_geometry = true;
  const InspectResult result = run_inspect(options);
  const nlohmann::json json = inspect_json(options, result, "mm");
  EXPECT_EQ(json.at("features").dump(), j.at("features").dump());  // the library call gives the CLI's figures
  const html::Page page = inspect_report(options, result, json, "");
  std::size_t feature_rows = 0;
  for (const html::Section& section : page.sections) {
    for (const html::Table& table : section.tables) {
      if (table.title == "Holes and bosses") feature_rows += table.rows.size();
    }
  }
  EXPECT_EQ(feature_rows, 3u);
  // 9 measured faces (id, points, mean .. form) and 3 features (id, points, diameter, nominal, position, form).
  EXPECT_GE(test::expect_cells_show_the_json(page), 9u * 6u + 3u * 6u);
  const test::RunResult text = test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step,
                                                       "--tolerances", dir.file("limits.csv")});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("feature 2   hole, faces " + std::to_string(faces_a[0]) + "+" + std::to_string(faces_a[1])),
            std::string::npos)
      << text.out;
}

// A hole with no scan points cannot be judged: its feature is there (points 0, not fitted), its verdict not measured,
// and the job's verdict "incomplete" (nothing failed).
TEST(InspectFeatures, AnUnscannedHoleIsIncomplete) {
  test::TempDir dir;
  const TopoDS_Shape shape = block_with_three_holes();
  const std::string step = dir.file("part.step");
  const CadFaces cad = test::write_step(shape, step);
  std::size_t face_c = 0;
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    if (cad.faces[f].type == CadSurfaceType::kCylinder && &hole_of(cad.faces[f]) == &kHoleC) face_c = f + 1;
  }
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& p : scan_of(shape, cad, 9)) {
    if ((p.head<2>() - kHoleC.centre).norm() > kHoleC.radius_mm + 1.0) points.push_back(p);
  }
  test::write_scan(dir.file("scan.ply"), points);
  test::write_bytes(dir.file("limits.csv"), "face,diameter_lower_mm,diameter_upper_mm\n" + std::to_string(face_c) +
                                                ",7.95,8.05\n");
  InspectOptions options;
  options.scan_path = dir.file("scan.ply");
  options.reference_path = step;
  options.tolerances_path = dir.file("limits.csv");
  const InspectResult r = run_inspect(options);
  ASSERT_TRUE(r.ok) << r.termination;
  ASSERT_EQ(r.features.size(), 3u);
  const FeatureInspection& c = feature_with(r, face_c);
  EXPECT_EQ(c.measured.points, 0u);
  EXPECT_FALSE(c.measured.fitted);
  ASSERT_TRUE(c.verdict.has_value());
  EXPECT_FALSE(c.verdict->measured);
  EXPECT_EQ(r.verdict, "incomplete");
  for (const FeatureInspection& f : r.features) {
    if (&f != &c) {
      EXPECT_FALSE(f.verdict.has_value());  // the file limits C only
    }
  }
}

TEST(InspectFeatures, BadFeatureLimitsAreExitTwo) {
  test::TempDir dir;
  const TopoDS_Shape shape = block_with_three_holes();
  const std::string step = dir.file("part.step");
  const CadFaces cad = test::write_step(shape, step);
  std::vector<std::size_t> faces_c;
  std::size_t plane = 0;
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    if (cad.faces[f].type == CadSurfaceType::kPlane && plane == 0) plane = f + 1;
    if (cad.faces[f].type == CadSurfaceType::kCylinder && &hole_of(cad.faces[f]) == &kHoleC) faces_c.push_back(f + 1);
  }
  ASSERT_EQ(faces_c.size(), 2u);
  test::write_scan(dir.file("scan.ply"), scan_of(shape, cad, 5));
  const auto run_with = [&](const std::string& limits) {
    test::write_bytes(dir.file("limits.csv"), limits);
    return test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step, "--tolerances",
                                   dir.file("limits.csv"), "--out-faces", dir.file("faces.csv")});
  };
  const std::string header = "face,diameter_lower_mm,diameter_upper_mm,position_mm\n";
  const test::RunResult twice = run_with(header + std::to_string(faces_c[0]) + ",7.9,8.1,\n" +
                                         std::to_string(faces_c[1]) + ",,,0.1\n");
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.err.find("limits.csv:3: face " + std::to_string(faces_c[1]) +
                           " is on the same hole or boss as the face of line 2"),
            std::string::npos)
      << twice.err;
  const test::RunResult on_plane = run_with(header + std::to_string(plane) + ",7.9,8.1,\n");
  EXPECT_EQ(on_plane.exit_code, 2);
  EXPECT_NE(on_plane.err.find("is a plane: diameter and position limits are for holes and bosses"), std::string::npos)
      << on_plane.err;
  const test::RunResult reversed = run_with(header + std::to_string(faces_c[0]) + ",8.1,7.9,\n");
  EXPECT_EQ(reversed.exit_code, 2);
  EXPECT_NE(reversed.err.find("diameter_lower_mm 8.1 is above diameter_upper_mm 7.9"), std::string::npos)
      << reversed.err;
  const test::RunResult zero = run_with(header + std::to_string(faces_c[0]) + ",,,0\n");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("position_mm must be > 0"), std::string::npos) << zero.err;
  const test::RunResult no_limit_column = run_with("face,comment\n1,x\n");
  EXPECT_EQ(no_limit_column.exit_code, 2);
  EXPECT_NE(no_limit_column.err.find("no limit column"), std::string::npos) << no_limit_column.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("faces.csv")));  // no partial output
}

}  // namespace
}  // namespace conform
