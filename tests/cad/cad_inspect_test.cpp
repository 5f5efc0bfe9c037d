// `conform inspect` (issue 33) on a generated part with known errors: a 80 x 60 x 20 mm block with two 12 mm through
// holes, made with OpenCASCADE and written as STEP. The scan is sampled on its exact faces and each face is given a
// known error along its outward normal: the top bowed (0.04 mm), the side x = 80 tilted (0.1 deg), hole A oversize
// (+0.05 mm in radius), hole B shifted (+0.1 mm in x); Gaussian noise (0.005 mm) on all; the bottom half scanned,
// the side y = 0 not at all; points off the part (a fixture 3-8 mm above the top, a wall standing on it). The scan is
// moved into its own frame and the transform given back, as `conform align --out-transform` writes it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>
#include <nlohmann/json.hpp>

#include "cad_shapes.h"
#include "conform/core/cad_faces.h"
#include "conform/core/io.h"
#include "conform/core/transform_io.h"
#include "conform/pipelines/inspect/inspect.h"
#include "conform/pipelines/inspect/inspect_json.h"
#include "conform/pipelines/inspect/inspect_report.h"
#include "inspect_scans.h"
#include "report_page_checks.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

constexpr double kBow = 0.04, kTiltDeg = 0.1, kOversize = 0.05, kShift = 0.1, kNoise = 0.005, kRadius = 6.0;

TopoDS_Shape block_with_two_holes() {
  TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 80.0, 60.0, 20.0).Shape();
  for (const double x : {20.0, 60.0}) {
    const TopoDS_Shape drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 30, -5), gp::DZ()), kRadius, 30.0).Shape();
    part = BRepAlgoAPI_Cut(part, drill).Shape();
  }
  return part;
}

enum class Role { kTop, kBottom, kHiddenSide, kTiltedSide, kOtherSide, kOversizeHole, kShiftedHole };

Role role_of(const CadFace& f) {
  if (f.type == CadSurfaceType::kCylinder) return f.origin_mm.x() < 40.0 ? Role::kOversizeHole : Role::kShiftedHole;
  if (f.axis.z() > 0.5) return Role::kTop;
  if (f.axis.z() < -0.5) return Role::kBottom;
  if (f.axis.y() < -0.5) return Role::kHiddenSide;
  if (f.axis.x() > 0.5) return Role::kTiltedSide;
  return Role::kOtherSide;
}

// The known error of the surface at p (on the nominal face), along the face's outward normal, mm.
double error_at(Role role, const Eigen::Vector3d& p) {
  switch (role) {
    case Role::kTop:
      return kBow * std::sin(M_PI * p.x() / 80.0) * std::sin(M_PI * p.y() / 60.0);
    case Role::kTiltedSide:
      return (p.z() - 10.0) * std::tan(kTiltDeg * M_PI / 180.0);
    case Role::kOversizeHole:
      return -kOversize;  // the wall moves away from the axis, into the material: outside (the hole) is towards it
    case Role::kShiftedHole: {
      // Along the radial direction u from the nominal axis, the shifted wall (axis moved by s) is at
      // r = s.u + sqrt(R^2 - |s|^2 + (s.u)^2).
      const Eigen::Vector2d u = (p.head<2>() - Eigen::Vector2d(60.0, 30.0)).normalized();
      const double su = kShift * u.x();
      return -(su + std::sqrt(kRadius * kRadius - kShift * kShift + su * su) - kRadius);
    }
    default:
      return 0.0;
  }
}

struct GeneratedScan {
  std::vector<Eigen::Vector3d> points;  // part frame
  std::vector<std::vector<double>> truth;  // per face index, the true deviation of each of its points
  std::size_t off_part = 0;
  std::size_t wall_near = 0;  // points of the wall within 0.5 mm of the top
};

GeneratedScan generate(const TopoDS_Shape& part, const CadFaces& cad) {
  GeneratedScan scan;
  const test::SurfaceSample s = test::sample_surface(part, 30000, 0.0, 5);
  std::mt19937_64 random(9);
  std::normal_distribution<double> noise(0.0, kNoise);
  scan.truth.resize(cad.faces.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto f = static_cast<std::size_t>(s.face[i]);
    const Role role = role_of(cad.faces[f]);
    if (role == Role::kHiddenSide || (role == Role::kBottom && s.points[i].x() > 40.0)) continue;
    const double d = error_at(role, s.points[i]) + noise(random);
    scan.points.push_back(s.points[i] + d * s.normals[i]);
    scan.truth[f].push_back(d);
  }
  std::uniform_real_distribution<double> x_of(5.0, 75.0), y_of(5.0, 55.0), z_of(23.0, 28.0);
  for (int i = 0; i < 300; ++i, ++scan.off_part) scan.points.emplace_back(x_of(random), y_of(random), z_of(random));
  // A wall standing on the top at x = 40 (a clamp): within the distance cut of the top near its foot, its normal
  // along x, not the top's.
  for (int k = 0; k < 20; ++k) {
    const double z = 20.15 + 0.1 * k;
    for (int j = 0; j < 100; ++j, ++scan.off_part) scan.points.emplace_back(40.0, 5.0 + 0.1 * j, z);
    if (z < 20.5) scan.wall_near += 100;
  }
  return scan;
}

using test::inspect_in_part_frame;
using test::write_scan;
const auto& mean = test::mean_of;

TEST(InspectCommand, KnownFormSizeAndPositionErrorsAreMeasured) {
  test::TempDir dir;
  const TopoDS_Shape part = block_with_two_holes();
  const std::string step = dir.file("part.step");
  test::write_cad(part, step, test::CadFormat::kStep, "MM");
  const CadFaces cad = read_cad_faces(step, CadReadOptions{}, nullptr, nullptr);
  ASSERT_EQ(cad.faces.size(), 8u);
  const GeneratedScan scan = generate(part, cad);

  // The scan in a frame of its own: rotated 2 deg about (1, 2, 3) and moved (5, -3, 2) mm.
  Eigen::Isometry3d T_scan_ref = Eigen::Isometry3d::Identity();
  T_scan_ref.rotate(Eigen::AngleAxisd(2.0 * M_PI / 180.0, Eigen::Vector3d(1, 2, 3).normalized()));
  T_scan_ref.translation() = Eigen::Vector3d(5.0, -3.0, 2.0);
  std::vector<Eigen::Vector3d> moved;
  for (const Eigen::Vector3d& p : scan.points) moved.push_back(T_scan_ref * p);
  write_scan(dir.file("scan.ply"), moved);
  write_transform(dir.file("T_ref_scan.txt"), T_scan_ref.inverse());

  const test::RunResult r =
      test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step, "--transform",
                              dir.file("T_ref_scan.txt"), "--out-faces", dir.file("faces.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j.at("ok").get<bool>());
  EXPECT_NEAR(j.at("scan_noise_mm").get<double>(), kNoise, 0.002);
  EXPECT_EQ(j.at("max_distance_mm").get<double>(), 0.5);  // 20 noise sigmas are less than the 0.5 mm floor
  // Every point off the part is on no face: the fixture beyond the cut, the wall's foot by its normal.
  const std::size_t on_part = scan.points.size() - scan.off_part;
  EXPECT_GE(j.at("unassigned_beyond_distance").get<std::size_t>(), scan.off_part - scan.wall_near);
  EXPECT_GE(j.at("unassigned_normal_mismatch").get<std::size_t>(), scan.wall_near);
  EXPECT_LE(j.at("assigned").get<std::size_t>(), on_part);
  EXPECT_GE(j.at("assigned").get<std::size_t>(), static_cast<std::size_t>(0.95 * static_cast<double>(on_part)));

  const nlohmann::json& faces = j.at("faces");
  ASSERT_EQ(faces.size(), cad.faces.size());
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    const nlohmann::json& face = faces[f];
    const Role role = role_of(cad.faces[f]);
    SCOPED_TRACE("face " + std::to_string(f + 1) + ": " + face.dump());
    EXPECT_EQ(face.at("id").get<std::size_t>(), f + 1);
    EXPECT_EQ(face.at("deviation_to"), "exact surface");
    if (role == Role::kHiddenSide) {
      EXPECT_EQ(face.at("points").get<int>(), 0);
      EXPECT_TRUE(face.at("mean_mm").is_null());
      continue;
    }
    // Most of the face's points are assigned to it (a few along its edges fail the normal check).
    const auto points = face.at("points").get<std::size_t>();
    EXPECT_GE(points, static_cast<std::size_t>(0.9 * static_cast<double>(scan.truth[f].size())));
    EXPECT_LE(points, scan.truth[f].size() + 5);
    // The mean deviation is the known error's mean over the face, within 0.002 mm.
    EXPECT_NEAR(face.at("mean_mm").get<double>(), mean(scan.truth[f]), 0.002);
    const double form = face.at("form_mm").get<double>();
    switch (role) {
      case Role::kTop:  // bowed: flatness is the bow plus the noise's 99 % zone (about 5.2 sigma)
        EXPECT_GT(form, kBow);
        EXPECT_LT(form, kBow + 7.0 * kNoise);
        EXPECT_LT(face.at("angle_to_nominal_deg").get<double>(), 0.005);
        EXPECT_LT(face.at("max_mm").get<double>(), kBow + 5.0 * kNoise);  // the wall's foot is not on it
        break;
      case Role::kTiltedSide:
        EXPECT_NEAR(face.at("angle_to_nominal_deg").get<double>(), kTiltDeg, 0.005);
        EXPECT_LT(form, 7.0 * kNoise);  // tilted, not bent: flat to the noise
        EXPECT_NEAR(face.at("min_mm").get<double>(), -10.0 * std::tan(kTiltDeg * M_PI / 180.0), 4.0 * kNoise);
        break;
      case Role::kOversizeHole:
        EXPECT_NEAR(face.at("radius_mm").get<double>(), kRadius + kOversize, 0.002);
        EXPECT_EQ(face.at("nominal_radius_mm").get<double>(), kRadius);
        EXPECT_LT(face.at("axis_offset_mm").get<double>(), 0.003);
        EXPECT_LT(face.at("position_mm").get<double>(), 0.006);
        EXPECT_NEAR(face.at("diameter_mm").get<double>(), 2.0 * (kRadius + kOversize), 0.004);
        EXPECT_LT(form, 7.0 * kNoise);
        break;
      case Role::kShiftedHole:
        EXPECT_NEAR(face.at("radius_mm").get<double>(), kRadius, 0.002);
        EXPECT_NEAR(face.at("axis_offset_mm").get<double>(), kShift, 0.003);
        EXPECT_NEAR(face.at("axis_point_mm")[0].get<double>(), 60.0 + kShift, 0.003);
        EXPECT_NEAR(face.at("position_mm").get<double>(), 2.0 * kShift, 0.006);  // a diameter zone
        EXPECT_NEAR(face.at("length_mm").get<double>(), 20.0, 0.5);
        EXPECT_TRUE(face.at("perpendicularity_mm").is_null());  // no datums
        EXPECT_NEAR(face.at("max_mm").get<double>(), kShift, 4.0 * kNoise);
        EXPECT_NEAR(face.at("min_mm").get<double>(), -kShift, 4.0 * kNoise);
        EXPECT_LT(form, 7.0 * kNoise);  // about the fitted cylinder the shift is gone
        break;
      default:  // the untouched faces, the bottom half scanned
        EXPECT_LT(face.at("angle_to_nominal_deg").get<double>(), 0.01);
        EXPECT_LT(form, 7.0 * kNoise);
        break;
    }
  }
  // The CSV holds the same faces.
  const std::string csv = test::read_bytes(dir.file("faces.csv"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), static_cast<long>(cad.faces.size()) + 1);

  // Tolerances: the bowed top's flatness (0.053 mm measured) over a 0.05 limit fails; the oversize hole's profile
  // (its wall 0.05 mm into the material) fails a -0.03 limit; the shifted hole passes +-0.15 and a form of 0.04; the
  // side that was not scanned cannot be judged. The job ran: exit 0, the verdict in the output.
  std::string table = "face,lower_mm,upper_mm,form_mm\n";
  std::size_t top = 0, oversize = 0, shifted = 0, hidden = 0;
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    const Role role = role_of(cad.faces[f]);
    if (role == Role::kTop) top = f + 1;
    if (role == Role::kOversizeHole) oversize = f + 1;
    if (role == Role::kShiftedHole) shifted = f + 1;
    if (role == Role::kHiddenSide) hidden = f + 1;
  }
  table += std::to_string(top) + ",,,0.05\n" + std::to_string(oversize) + ",-0.03,0.03,\n" +
           std::to_string(shifted) + ",-0.15,0.15,0.04\n" + std::to_string(hidden) + ",-0.1,0.1,\n";
  test::write_bytes(dir.file("tolerances.csv"), table);
  const test::RunResult judged =
      test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step, "--transform",
                              dir.file("T_ref_scan.txt"), "--tolerances", dir.file("tolerances.csv"), "--json"});
  ASSERT_EQ(judged.exit_code, 0) << judged.err;
  const nlohmann::json v = nlohmann::json::parse(judged.out);
  EXPECT_EQ(v.at("verdict"), "fail");
  const nlohmann::json& vf = v.at("faces");
  EXPECT_EQ(vf[top - 1].at("tolerance").at("form_pass"), false);
  EXPECT_EQ(vf[top - 1].at("tolerance").at("pass"), false);
  EXPECT_EQ(vf[oversize - 1].at("tolerance").at("profile_pass"), false);
  EXPECT_EQ(vf[shifted - 1].at("tolerance").at("pass"), true);
  EXPECT_EQ(vf[hidden - 1].at("tolerance").at("measured"), false);
  EXPECT_TRUE(vf[hidden - 1].at("tolerance").at("pass").is_null());
  for (std::size_t f = 1; f <= cad.faces.size(); ++f) {  // the faces the file does not name have no verdict
    if (f != top && f != oversize && f != shifted && f != hidden) {
      EXPECT_FALSE(vf[f - 1].contains("tolerance"));
    }
  }

  // The report (in process, as `--report` builds it): the verdict, the scan over the CAD, every face's row tied to
  // the JSON and showing its value.
  InspectOptions options;
  options.scan_path = dir.file("scan.ply");
  options.reference_path = step;
  options.transform_path = dir.file("T_ref_scan.txt");
  options.tolerances_path = dir.file("tolerances.csv");
  options.keep_geometry = true;
  const InspectResult result = run_inspect(options);
  const nlohmann::json json = inspect_json(options, result, "mm");
  EXPECT_EQ(json.at("faces").dump(), v.at("faces").dump());  // the library call gives the CLI's figures
  const html::Page page = inspect_report(options, result, json, "");
  EXPECT_EQ(page.verdict.level, html::Level::kFail);
  EXPECT_EQ(result.scan_ref.vertices.size(), scan.points.size());
  EXPECT_GE(test::expect_cells_show_the_json(page), 7u * 6u);  // 7 measured faces: id, points, mean .. form
  // Each measured or toleranced face a layer of its own, the failing ones shown, red.
  std::size_t face_layers = 0, shown = 0;
  for (const html::SceneObject& o : page.scene.objects()) {
    if (o.name.rfind("face ", 0) != 0) continue;
    ++face_layers;
    if (o.visible) {
      ++shown;
      EXPECT_NE(o.name.find("FAIL"), std::string::npos) << o.name;
    }
  }
  EXPECT_EQ(face_layers, 8u);  // 7 measured, and the unscanned one named by the tolerances
  EXPECT_EQ(shown, 2u);        // the bowed top and the oversize hole

  // A tolerance file that names a face the CAD does not have is bad input: exit 2, naming the line.
  test::write_bytes(dir.file("bad.csv"), "face,lower_mm,upper_mm,form_mm\n9,-0.1,0.1,\n");
  const test::RunResult bad =
      test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step, "--transform",
                              dir.file("T_ref_scan.txt"), "--tolerances", dir.file("bad.csv")});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.csv:2: face 9 is not one of the CAD's faces 1..8"), std::string::npos) << bad.err;
}

// The best fit of the whole scan is pulled by the bowed top and the tilted side; the 3-2-1 datum fit on the bottom
// (A), the side x = 0 (B) and the side y = 60 (C), none of them in error, puts the scan back where the truth is.
TEST(InspectCommand, DatumFitUndoesTheBestFitsBias) {
  test::TempDir dir;
  const TopoDS_Shape part = block_with_two_holes();
  const std::string step = dir.file("part.step");
  test::write_cad(part, step, test::CadFormat::kStep, "MM");
  const CadFaces cad = read_cad_faces(step, CadReadOptions{}, nullptr, nullptr);
  const GeneratedScan scan = generate(part, cad);
  Eigen::Isometry3d T_scan_ref = Eigen::Isometry3d::Identity();
  T_scan_ref.rotate(Eigen::AngleAxisd(0.5 * M_PI / 180.0, Eigen::Vector3d(3, -1, 2).normalized()));
  T_scan_ref.translation() = Eigen::Vector3d(0.4, 0.3, -0.5);
  std::vector<Eigen::Vector3d> moved;
  for (const Eigen::Vector3d& p : scan.points) moved.push_back(T_scan_ref * p);
  write_scan(dir.file("scan.ply"), moved);
  std::size_t bottom = 0, side_x0 = 0, side_y60 = 0, top = 0, tilted = 0, shifted = 0;
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    const CadFace& face = cad.faces[f];
    const Role role = role_of(face);
    if (role == Role::kBottom) bottom = f + 1;
    if (role == Role::kTop) top = f + 1;
    if (role == Role::kTiltedSide) tilted = f + 1;
    if (role == Role::kShiftedHole) shifted = f + 1;
    if (face.type == CadSurfaceType::kPlane && face.axis.x() < -0.5) side_x0 = f + 1;
    if (face.type == CadSurfaceType::kPlane && face.axis.y() > 0.5) side_y60 = f + 1;
  }
  ASSERT_TRUE(bottom && side_x0 && side_y60 && top && tilted && shifted);
  const std::string datums = std::to_string(bottom) + "," + std::to_string(side_x0) + "," + std::to_string(side_y60);
  std::vector<nlohmann::json> runs;
  for (const bool with_datums : {false, true}) {
    std::vector<std::string> args = {"inspect", "--scan", dir.file("scan.ply"), "--reference", step, "--align",
                                     "best-fit", "--json"};
    if (with_datums) args.insert(args.end(), {"--datums", datums});
    const test::RunResult r = test::run(CONFORM_EXE, args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs.push_back(nlohmann::json::parse(r.out));
    EXPECT_NE(runs.back().at("align_trust"), "no");
  }
  const nlohmann::json& fit = runs[0].at("faces");
  const nlohmann::json& datum = runs[1].at("faces");
  // The truth: the top's mean deviation is its bow's mean, the bottom's 0, the tilt 0.1 deg, the shift 0.1 mm.
  const double top_truth = mean(scan.truth[top - 1]);
  EXPECT_NEAR(datum[top - 1].at("mean_mm").get<double>(), top_truth, 0.002);
  EXPECT_NEAR(datum[bottom - 1].at("mean_mm").get<double>(), 0.0, 0.001);
  EXPECT_NEAR(datum[tilted - 1].at("angle_to_nominal_deg").get<double>(), kTiltDeg, 0.005);
  EXPECT_NEAR(datum[shifted - 1].at("axis_offset_mm").get<double>(), kShift, 0.003);
  EXPECT_NEAR(datum[shifted - 1].at("position_mm").get<double>(), 2.0 * kShift, 0.006);
  // The holes are square to the bottom (datum A): their axes lean by the fit's noise only, over 20 mm.
  EXPECT_LT(datum[shifted - 1].at("perpendicularity_mm").get<double>(), 0.005);
  // The best fit is measurably off the truth on the same faces (which is why datums exist).
  EXPECT_GT(std::abs(fit[top - 1].at("mean_mm").get<double>() - top_truth), 0.005);
  const nlohmann::json& d = runs[1].at("datums");
  EXPECT_EQ(d.at("faces").size(), 3u);
  EXPECT_GT(d.at("rotation_deg").get<double>(), 0.001);
}

// A part made right reads as right: the filleted block (planes, R 10 fillets, 45-degree chamfer cones round its
// corners, a pocket), scanned with noise only (0.005 mm), every face measured to its exact surface: no mean deviation
// beyond 0.002 mm, no form beyond the noise's zone, the fillets' radius 10 mm within 0.005 mm, every cylinder fitted.
TEST(InspectCommand, APerfectPartShowsOnlyItsNoise) {
  test::TempDir dir;
  const TopoDS_Shape part = test::filleted_block();
  const std::string step = dir.file("block.step");
  test::write_cad(part, step, test::CadFormat::kStep, "MM");
  const test::SurfaceSample s = test::sample_surface(part, 30000, kNoise, 21);
  write_scan(dir.file("scan.ply"), s.points);
  const InspectResult r = inspect_in_part_frame(dir.file("scan.ply"), step);
  ASSERT_TRUE(r.ok) << r.termination;
  EXPECT_GE(r.assigned, static_cast<std::size_t>(0.93 * static_cast<double>(s.points.size())));
  std::size_t cones = 0, fillets = 0;
  for (const FaceInspection& f : r.faces) {
    SCOPED_TRACE("face " + std::to_string(f.id) + " " + to_string(f.nominal.type) + ", " + std::to_string(f.points) +
                 " points");
    ASSERT_TRUE(f.exact);
    if (f.points < InspectOptions{}.min_fit_points) continue;
    EXPECT_LT(std::abs(f.deviation.mean_mm), 0.002);
    EXPECT_LT(f.form.width_mm, 7.0 * kNoise);
    if (f.nominal.type == CadSurfaceType::kCone) ++cones;
    if (f.nominal.type == CadSurfaceType::kCylinder) {
      ++fillets;
      ASSERT_TRUE(f.fitted) << f.fit_note;
      EXPECT_NEAR(f.radius_mm, 10.0, 0.005);
      EXPECT_LT(f.axis_offset_mm, 0.01);
    }
    if (f.nominal.type == CadSurfaceType::kPlane) {
      ASSERT_TRUE(f.fitted) << f.fit_note;
      // The tilt a least-squares plane takes from the noise: sigma sqrt(12) / (L sqrt(N)) rad across a width L; L taken
      // as half the square root of the face's area (a 16 x 5 mm pocket wall: 4.5 mm), 4 of those standard deviations.
      const double width_mm = 0.5 * std::sqrt(f.nominal.area_mm2);
      const double limit_deg =
          4.0 * kNoise * std::sqrt(12.0) / (width_mm * std::sqrt(static_cast<double>(f.points))) * 180.0 / M_PI;
      EXPECT_LT(f.angle_to_nominal_deg, limit_deg);
    }
  }
  EXPECT_EQ(fillets, 4u);
  EXPECT_GE(cones, 1u);
}

// A ball R 20 mm made 0.03 mm oversize and its centre moved 0.05 mm along x, a cap of it scanned (z > 5 mm) with
// noise: the least-squares sphere finds both; its sphericity is the noise's zone.
TEST(InspectCommand, AnOversizeShiftedSphereIsMeasured) {
  test::TempDir dir;
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 20.0).Shape();
  const std::string step = dir.file("ball.step");
  test::write_cad(ball, step, test::CadFormat::kStep, "MM");
  const test::SurfaceSample s = test::sample_surface(ball, 20000, 0.0, 31);
  std::mt19937_64 random(4);
  std::normal_distribution<double> noise(0.0, kNoise);
  const Eigen::Vector3d shift(0.05, 0.0, 0.0);
  std::vector<Eigen::Vector3d> cap;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    if (s.points[i].z() < 5.0) continue;
    cap.push_back(s.points[i] * (20.03 / 20.0) + shift + noise(random) * s.normals[i]);
  }
  write_scan(dir.file("scan.ply"), cap);
  const InspectResult r = inspect_in_part_frame(dir.file("scan.ply"), step);
  ASSERT_TRUE(r.ok) << r.termination;
  ASSERT_EQ(r.faces.size(), 1u);
  const FaceInspection& f = r.faces[0];
  ASSERT_EQ(f.nominal.type, CadSurfaceType::kSphere);
  ASSERT_TRUE(f.fitted) << f.fit_note;
  EXPECT_EQ(f.form_reference, "least-squares sphere");
  EXPECT_NEAR(f.radius_mm, 20.03, 0.003);
  EXPECT_NEAR(f.centre_offset_mm, 0.05, 0.005);
  EXPECT_NEAR(f.centre_mm.x(), 0.05, 0.005);
  EXPECT_LT(f.form.width_mm, 7.0 * kNoise);
  EXPECT_GT(f.deviation.mean_mm, 0.0);  // oversize: material outside the CAD
}

TEST(InspectCommand, BadUsageIsExitTwo) {
  test::TempDir dir;
  const test::RunResult mesh_reference =
      test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("s.ply"), "--reference", dir.file("part.stl")});
  EXPECT_EQ(mesh_reference.exit_code, 2);
  EXPECT_NE(mesh_reference.err.find("needs the CAD's faces"), std::string::npos) << mesh_reference.err;
  const test::RunResult both = test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("s.ply"), "--reference",
                                                       dir.file("p.step"), "--transform", dir.file("T.txt"),
                                                       "--align", "best-fit"});
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.err.find("exclude each other"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace conform
