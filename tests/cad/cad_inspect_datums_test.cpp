// `conform inspect --datums` with holes as datums: the 3-2-1 fit with a plane primary and a hole as secondary or
// tertiary recovers a known pose. The part: an 80 x 60 x 20 mm block (OpenCASCADE, STEP) with hole A (R 6 at (20, 30),
// split into two half-cylinder faces) and hole B (R 6 at (60, 30)); as made, hole A's axis is (0.1, -0.05) mm off,
// the rest right. The scan: noise 0.005 mm, the side y = 0 unseen, moved by a known 0.2-degree turn and 0.1-0.15 mm
// shift. The datum frame is where the datums are: the expected T_ref_scan is the scan's true pose followed by the
// shift (and turn) that puts the made datums on their nominals; every face is judged from there.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
#include "conform/core/constants.h"
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

constexpr double kNoise = 0.005;
const test::MadeHole kHoleA{{20.0, 30.0}, 6.0, 0.0, {0.1, -0.05}};
const test::MadeHole kHoleB{{60.0, 30.0}, 6.0, 0.0, {0.0, 0.0}};

struct Ids {
  std::size_t bottom = 0, top = 0, side_x0 = 0, side_x80 = 0, side_y60 = 0, hole_a = 0, hole_b = 0;
};

Ids ids_of(const CadFaces& cad) {
  Ids ids;
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    const CadFace& face = cad.faces[f];
    if (face.type == CadSurfaceType::kCylinder) {
      std::size_t& hole = face.origin_mm.x() < 40.0 ? ids.hole_a : ids.hole_b;
      if (hole == 0) hole = f + 1;  // a split hole: its first face names it
      continue;
    }
    if (face.axis.z() < -0.5) ids.bottom = f + 1;
    if (face.axis.z() > 0.5) ids.top = f + 1;
    if (face.axis.x() < -0.5) ids.side_x0 = f + 1;
    if (face.axis.x() > 0.5) ids.side_x80 = f + 1;
    if (face.axis.y() > 0.5) ids.side_y60 = f + 1;
  }
  return ids;
}

// x -> R (x - centre) + centre about z through `centre`.
Eigen::Isometry3d turn_about_z(double angle_rad, const Eigen::Vector3d& centre) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = centre - T.linear() * centre;
  return T;
}

Eigen::Isometry3d shift(const Eigen::Vector3d& by) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = by;
  return T;
}

// The largest distance between where two poses put the part's corners, mm.
double pose_difference_mm(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  double worst = 0.0;
  for (const double x : {0.0, 80.0}) {
    for (const double y : {0.0, 60.0}) {
      for (const double z : {0.0, 20.0}) worst = std::max(worst, (a * Eigen::Vector3d(x, y, z) - b *
                                                                  Eigen::Vector3d(x, y, z)).norm());
    }
  }
  return worst;
}

class InspectDatums : public ::testing::Test {
 protected:
  void SetUp() override {
    TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 80.0, 60.0, 20.0).Shape();
    part = test::drill_split_hole(part, 20.0, 30.0, 6.0, -5.0, 25.0);
    part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(60, 30, -5), gp::DZ()), 6.0, 30.0).Shape())
               .Shape();
    step_ = dir_.file("part.step");
    cad_ = test::write_step(part, step_);
    ids_ = ids_of(cad_);
    ASSERT_TRUE(ids_.bottom && ids_.top && ids_.side_x0 && ids_.side_x80 && ids_.side_y60 && ids_.hole_a &&
                ids_.hole_b);
    part_ = part;
  }

  // The made part scanned (seeded), in a frame of its own: p_scan = T_scan_ref p.
  void scan(std::uint64_t seed) {
    const test::SurfaceSample s = test::sample_surface(part_, 30000, 0.0, seed);
    Random random(seed + 7);
    T_scan_ref_ = Eigen::Isometry3d::Identity();
    T_scan_ref_.rotate(Eigen::AngleAxisd(radians(0.2), Eigen::Vector3d(1, -2, 3).normalized()));
    T_scan_ref_.translation() = Eigen::Vector3d(0.15, -0.1, 0.12);
    std::vector<Eigen::Vector3d> points;
    point_face_.clear();
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const CadFace& f = cad_.faces[static_cast<std::size_t>(s.face[i])];
      if (f.type == CadSurfaceType::kPlane && f.axis.y() < -0.5) continue;
      double error = 0.0;
      if (f.type == CadSurfaceType::kCylinder && f.origin_mm.x() < 40.0) error = test::hole_error(kHoleA, s.points[i]);
      points.push_back(T_scan_ref_ * (s.points[i] + (error + kNoise * random.normal()) * s.normals[i]));
      point_face_.push_back(static_cast<std::size_t>(s.face[i]));
    }
    test::write_scan(dir_.file("scan.ply"), points);
    points_ = points;
  }

  InspectResult inspect(const std::vector<std::size_t>& datums, bool best_fit = false, bool keep = false) const {
    InspectOptions options;
    options.best_fit = best_fit;
    options.keep_geometry = keep;
    options.scan_path = dir_.file("scan.ply");
    options.reference_path = step_;
    options.max_distance_mm = 2.0;  // the scan is up to 0.4 mm off the part before the datum fit
    options.datum_faces = datums;
    return run_inspect(options);
  }

  test::TempDir dir_;
  std::string step_;
  CadFaces cad_;
  Ids ids_;
  TopoDS_Shape part_;
  Eigen::Isometry3d T_scan_ref_ = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3d> points_;  // the scan as written, in its own frame
  std::vector<std::size_t> point_face_;  // each point's face as sampled, 0-based
};

const std::uint64_t kSeeds[] = {2, 13, 29};

// A (the bottom), B (hole A), C (the side y = 60): hole A's made axis onto its nominal (the part moves by -(0.1,
// -0.05)), the turn about it by the side y = 60; the side y = 60 keeps hole A's 0.05 mm.
TEST_F(InspectDatums, APlaneThenAHoleThenAPlane) {
  for (const std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    scan(seed);
    const InspectResult r = inspect({ids_.bottom, ids_.hole_a, ids_.side_y60});
    ASSERT_TRUE(r.ok) << r.termination;
    const Eigen::Isometry3d expected = shift(Eigen::Vector3d(-0.1, 0.05, 0.0)) * T_scan_ref_.inverse();
    EXPECT_LT(pose_difference_mm(r.T_ref_scan, expected), 0.002);
    EXPECT_LT(degrees(Eigen::AngleAxisd(r.T_ref_scan.linear() * expected.linear().transpose()).angle()), 0.003);
    ASSERT_EQ(r.datum_moved_mm.size(), 3u);
    const FaceInspection& hole_a = r.faces[ids_.hole_a - 1];
    EXPECT_LT(r.features[0].measured.position_mm, 0.008);  // the datum is where it should be
    EXPECT_EQ(r.features[0].faces.size(), 2u);
    EXPECT_TRUE(hole_a.fitted);
    const FaceInspection& hole_b = r.faces[ids_.hole_b - 1];
    EXPECT_NEAR(hole_b.axis_offset_mm, std::hypot(0.1, 0.05), 0.003);
    EXPECT_NEAR(hole_b.axis_point_mm.x(), 59.9, 0.003);
    EXPECT_NEAR(hole_b.axis_point_mm.y(), 30.05, 0.003);
    EXPECT_NEAR(r.faces[ids_.side_x0 - 1].deviation.mean_mm, 0.1, 0.002);    // the part sits 0.1 mm towards -x
    EXPECT_NEAR(r.faces[ids_.side_x80 - 1].deviation.mean_mm, -0.1, 0.002);
    EXPECT_NEAR(r.faces[ids_.side_y60 - 1].deviation.mean_mm, 0.05, 0.002);
    EXPECT_LT(r.faces[ids_.side_y60 - 1].angle_to_nominal_deg, 0.005);
    EXPECT_NEAR(r.faces[ids_.bottom - 1].deviation.mean_mm, 0.0, 0.001);
    EXPECT_LT(hole_b.perpendicularity_mm, 0.005);
  }
}

// A, B (hole A), C (hole B): the turn about hole A's axis puts hole B's axis in the nominal direction: the made
// direction (39.9, 0.05) turned by -atan(0.05 / 39.9) = -0.0718 deg; hole B then sits 40 - |(39.9, 0.05)| short.
TEST_F(InspectDatums, APlaneThenTwoHoles) {
  const double turn = -std::atan2(0.05, 39.9);
  for (const std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    scan(seed);
    const InspectResult r = inspect({ids_.bottom, ids_.hole_a, ids_.hole_b});
    ASSERT_TRUE(r.ok) << r.termination;
    const Eigen::Isometry3d expected = turn_about_z(turn, Eigen::Vector3d(20, 30, 0)) *
                                       shift(Eigen::Vector3d(-0.1, 0.05, 0.0)) * T_scan_ref_.inverse();
    EXPECT_LT(pose_difference_mm(r.T_ref_scan, expected), 0.002);
    const FaceInspection& side = r.faces[ids_.side_y60 - 1];
    EXPECT_NEAR(side.angle_to_nominal_deg, degrees(-turn), 0.004);
    const FaceInspection& hole_b = r.faces[ids_.hole_b - 1];
    EXPECT_NEAR(hole_b.axis_point_mm.x(), 20.0 + std::hypot(39.9, 0.05), 0.003);
    EXPECT_NEAR(hole_b.axis_point_mm.y(), 30.0, 0.003);
  }
}

// A, B (the side x = 0), C (hole A): the side fixes x (it is right), hole A moves the part along y only: hole A's
// x error stays, its y error is taken out.
TEST_F(InspectDatums, TwoPlanesThenAHole) {
  for (const std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    scan(seed);
    const InspectResult r = inspect({ids_.bottom, ids_.side_x0, ids_.hole_a});
    ASSERT_TRUE(r.ok) << r.termination;
    const Eigen::Isometry3d expected = shift(Eigen::Vector3d(0.0, 0.05, 0.0)) * T_scan_ref_.inverse();
    EXPECT_LT(pose_difference_mm(r.T_ref_scan, expected), 0.002);
    const FeatureInspection& a = r.features[0];
    EXPECT_NEAR(a.measured.axis_point_mm.x(), 20.1, 0.003);
    EXPECT_NEAR(a.measured.axis_point_mm.y(), 30.0, 0.003);
    EXPECT_NEAR(r.faces[ids_.side_x0 - 1].deviation.mean_mm, 0.0, 0.002);
  }
}

// Beside the datum frame, the best fit. With A (the bottom), B (hole A), C (the side y = 60) the datum frame is the
// truth moved by (-0.1, 0.05, 0) mm (hole A's made axis onto its nominal); the best fit of the whole scan stays near
// the truth (hole A's wall pulls it 0.0013 mm in x over seeds 2, 13, 29). So: the best fit's pose and figures are
// those of a separate `--align best-fit` run (the same ICP from the same start: within 1e-5 mm, seen < 1e-6); each
// face's mean at it is its points as written, moved by that pose, against their sampled faces (an independent sum,
// within 0.001 mm, seen 0.0007: points near edges land on the other face or none); the two poses are hypot(0.1, 0.05)
// = 0.1118 mm apart at the part (within 0.003, seen 0.1111-0.1117); the side x = 0 sits 0.1 mm out in the datum
// frame and within 0.005 mm (seen 0.0014) at the best fit; hole A is on its nominal in the datum frame and 2 x 0.11 mm
// off at the best fit, hole B the other way round. Without datums nothing is added.
TEST_F(InspectDatums, TheBestFitBesideTheDatumFrame) {
  for (const std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    scan(seed);
    const InspectResult r = inspect({ids_.bottom, ids_.hole_a, ids_.side_y60}, false, seed == 2);
    ASSERT_TRUE(r.ok) << r.termination;
    ASSERT_TRUE(r.best_fit.computed);
    ASSERT_TRUE(r.best_fit.converged);
    ASSERT_EQ(r.best_fit.faces.size(), r.faces.size());
    ASSERT_EQ(r.best_fit.features.size(), r.features.size());

    // The same pose as --align best-fit, and its figures the same.
    const InspectResult aligned = inspect({}, true);
    ASSERT_TRUE(aligned.ok) << aligned.termination;
    EXPECT_FALSE(aligned.best_fit.computed);
    EXPECT_LT(pose_difference_mm(r.best_fit.T_ref_scan, aligned.T_ref_scan), 1e-5);
    for (std::size_t f = 0; f < r.faces.size(); ++f) {
      SCOPED_TRACE("face " + std::to_string(f + 1));
      const FaceInspection& b = r.best_fit.faces[f];
      const FaceInspection& a = aligned.faces[f];
      if (a.points == 0) continue;
      EXPECT_EQ(b.points, a.points);
      EXPECT_NEAR(b.deviation.mean_mm, a.deviation.mean_mm, 1e-5);
      EXPECT_NEAR(b.deviation.std_mm, a.deviation.std_mm, 1e-5);
      EXPECT_NEAR(b.form.width_mm, a.form.width_mm, 1e-5);
    }

    // Each face's mean and the holes' position at the best fit from the points as written, by their sampled face.
    std::vector<double> sum(cad_.faces.size(), 0.0);
    std::vector<std::size_t> count(cad_.faces.size(), 0);
    double displacement = 0.0;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector3d q = r.best_fit.T_ref_scan * points_[i];
      sum[point_face_[i]] += analytic_signed_distance(cad_.faces[point_face_[i]], q);
      ++count[point_face_[i]];
      displacement = std::max(displacement, (r.T_ref_scan * points_[i] - q).norm());
    }
    for (std::size_t f = 0; f < cad_.faces.size(); ++f) {
      if (count[f] < 100) continue;
      EXPECT_NEAR(r.best_fit.faces[f].deviation.mean_mm, sum[f] / static_cast<double>(count[f]), 0.001)
          << "face " << f + 1;
    }
    EXPECT_NEAR(r.best_fit.displacement_mm, displacement, 1e-6);
    EXPECT_NEAR(r.best_fit.displacement_mm, std::hypot(0.1, 0.05), 0.003);
    EXPECT_NEAR(r.best_fit.angle_deg,
                degrees(Eigen::AngleAxisd(r.T_ref_scan.linear() * r.best_fit.T_ref_scan.linear().transpose()).angle()),
                1e-6);
    EXPECT_LT(r.best_fit.angle_deg, 0.01);

    // Not a copy of the datum frame's figures: the side x = 0 and hole A.
    const double datum_side = r.faces[ids_.side_x0 - 1].deviation.mean_mm;
    const double best_side = r.best_fit.faces[ids_.side_x0 - 1].deviation.mean_mm;
    EXPECT_NEAR(datum_side, 0.1, 0.002);
    EXPECT_LT(std::abs(best_side), 0.005);
    EXPECT_GT(datum_side - best_side, 0.09);
    EXPECT_LT(r.features[0].measured.position_mm, 0.008);  // the datum hole on its nominal
    EXPECT_NEAR(r.best_fit.features[0].measured.position_mm, 2.0 * std::hypot(0.1, 0.05), 0.008);
    EXPECT_NEAR(r.features[1].measured.position_mm, 2.0 * std::hypot(0.1, 0.05), 0.008);  // hole B: the other way
    EXPECT_LT(r.best_fit.features[1].measured.position_mm, 0.01);
    EXPECT_NEAR(2.0 * r.best_fit.features[0].measured.radius_mm, 2.0 * r.features[0].measured.radius_mm, 0.001);

    // The JSON: a best_fit object per face and feature, and the poses; none without datums.
    InspectOptions options;
    options.scan_path = dir_.file("scan.ply");
    options.reference_path = step_;
    options.datum_faces = {ids_.bottom, ids_.hole_a, ids_.side_y60};
    const nlohmann::json j = inspect_json(options, r, "mm");
    ASSERT_TRUE(j.at("best_fit").at("converged").get<bool>());
    EXPECT_EQ(j.at("best_fit").at("pose"), "--align best-fit on the scan as read");
    EXPECT_NEAR(j.at("best_fit").at("displacement_mm").get<double>(), displacement, 1e-6);
    const nlohmann::json& side = j.at("faces").at(ids_.side_x0 - 1);
    EXPECT_DOUBLE_EQ(side.at("best_fit").at("mean_mm").get<double>(), best_side);
    EXPECT_DOUBLE_EQ(side.at("mean_mm").get<double>(), datum_side);
    EXPECT_TRUE(j.at("features").at(0).at("best_fit").contains("position_mm"));
    InspectOptions plain = options;
    plain.datum_faces.clear();
    plain.best_fit = true;
    const nlohmann::json none = inspect_json(plain, aligned, "mm");
    EXPECT_FALSE(none.contains("best_fit"));
    EXPECT_FALSE(none.at("faces").at(0).contains("best_fit"));
    EXPECT_FALSE(none.at("features").at(0).contains("best_fit"));

    // The report: the best-fit columns beside the datum frame's, each cell showing its JSON value.
    if (seed != 2) continue;
    // After a transform (here the identity) the best fit is align's fine fit from it: the same pose.
    write_transform(dir_.file("identity.txt"), Eigen::Isometry3d::Identity());
    InspectOptions given = options;
    given.transform_path = dir_.file("identity.txt");
    given.max_distance_mm = 2.0;
    const InspectResult from_transform = run_inspect(given);
    ASSERT_TRUE(from_transform.best_fit.converged);
    EXPECT_LT(pose_difference_mm(from_transform.best_fit.T_ref_scan, r.best_fit.T_ref_scan), 0.001);
    options.keep_geometry = true;
    const html::Page page = inspect_report(options, r, j, "");
    std::size_t tables = 0, best_cells = 0;
    for (const html::Section& section : page.sections) {
      for (const html::Table& table : section.tables) {
        const auto has = [&](const std::string& h) {
          return std::find(table.header.begin(), table.header.end(), h) != table.header.end();
        };
        if (table.title == "Faces") {
          ++tables;
          EXPECT_TRUE(has("mean mm") && has("best-fit mean mm") && has("best-fit form mm"));
        }
        if (table.title == "Holes and bosses") {
          ++tables;
          EXPECT_TRUE(has("position mm") && has("best-fit position mm") && has("best-fit diameter mm"));
        }
        for (const auto& row : table.rows) {
          EXPECT_EQ(row.size(), table.header.size()) << table.title;
          for (const html::Cell& cell : row) best_cells += cell.json_pointer.find("/best_fit/") != std::string::npos;
        }
      }
    }
    EXPECT_EQ(tables, 2u);
    EXPECT_GE(best_cells, 6u * 5u + 2u * 2u);  // 6 scanned faces' 5 figures, the 2 holes' diameter and position
    EXPECT_GE(test::expect_cells_show_the_json(page), 6u * 10u);
  }
}

// What a hole cannot fix is refused by name (exit 2): a hole as primary; a hole not square to the primary; after a
// hole, a tertiary plane parallel to the primary.
TEST_F(InspectDatums, CombinationsThatFixNothingAreExitTwo) {
  scan(2);
  const auto run = [&](const std::vector<std::size_t>& d) {
    std::string list;
    for (const std::size_t id : d) list += (list.empty() ? "" : ",") + std::to_string(id);
    return test::run(CONFORM_EXE, {"inspect", "--scan", dir_.file("scan.ply"), "--reference", step_, "--max-distance",
                                   "2", "--datums", list});
  };
  const test::RunResult primary = run({ids_.hole_a, ids_.bottom});
  EXPECT_EQ(primary.exit_code, 2);
  EXPECT_NE(primary.err.find("the primary datum must be a plane"), std::string::npos) << primary.err;
  const test::RunResult askew = run({ids_.side_x0, ids_.hole_a});
  EXPECT_EQ(askew.exit_code, 2);
  EXPECT_NE(askew.err.find("axis is not square to the primary datum's plane"), std::string::npos) << askew.err;
  const test::RunResult parallel = run({ids_.bottom, ids_.hole_a, ids_.top});
  EXPECT_EQ(parallel.exit_code, 2);
  EXPECT_NE(parallel.err.find("does not fix the turn"), std::string::npos) << parallel.err;
  // And the CLI gives the pose the library does.
  const test::RunResult fine = test::run(CONFORM_EXE, {"inspect", "--scan", dir_.file("scan.ply"), "--reference",
                                                       step_, "--max-distance", "2", "--datums",
                                                       std::to_string(ids_.bottom) + "," +
                                                           std::to_string(ids_.hole_a) + "," +
                                                           std::to_string(ids_.side_y60),
                                                       "--json"});
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  const nlohmann::json j = nlohmann::json::parse(fine.out);
  EXPECT_EQ(j.at("datums").at("faces").size(), 3u);
  EXPECT_EQ(j.at("datums").at("moved_mm").size(), 3u);
}

}  // namespace
}  // namespace conform
