// Generated panels: the contour lies on the nominal surface at the opening's edge and has the asked spacing; the
// truth is the known deformation of the trajectory; the scan lies on the deformed surface within its noise; missing
// arcs remove points; the same seed gives the same data; bad options throw.

#include "conform/datasets/panel.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/core/error.h"
#include "conform/core/mesh_boundary.h"
#include "conform/core/triangle_index.h"
#include "conform/datasets/panel_shape.h"

namespace conform {
namespace {

PanelOptions small(PanelShape shape) {
  PanelOptions o;
  o.shape = shape;
  o.scan_points = 20000;
  o.contour_spacing_mm = 1.0;
  o.surface_edge_mm = 4.0;
  return o;
}

TEST(Panel, PlateContourTrajectoryAndTruth) {
  const PanelOptions o = small(PanelShape::kPlate);
  const PanelData d = generate_panel(o);
  // Ellipse 190 x 130 mm on a gently curved plate: Ramanujan's perimeter 1013.3 mm, 0.2% longer for the slope.
  EXPECT_NEAR(d.perimeter_mm, 1013.3, 3.0);
  EXPECT_EQ(d.contour.points.size(), static_cast<std::size_t>(std::lround(d.perimeter_mm)));
  EXPECT_TRUE(d.contour.closed);
  for (const Eigen::Vector3d& p : d.contour.points) {  // on z = x^2/2Rx + y^2/2Ry (exact formula)
    EXPECT_NEAR(p.z(), p.x() * p.x() / 5000.0 + p.y() * p.y() / 8000.0, 1e-9);
  }
  ASSERT_EQ(d.truth.points.size(), d.trajectory.points.size());
  for (std::size_t i = 0; i < d.trajectory.points.size(); i += 50) {
    EXPECT_LT((d.truth.points[i] - deform_point(o, d.trajectory.points[i])).norm(), 1e-12);
    EXPECT_NEAR(d.truth.normals[i].norm(), 1.0, 1e-12);
  }
  // The surface mesh's boundary: the opening's flank bottom and the band's outer rim, both closed.
  const std::vector<Polyline> loops = boundary_polylines(d.surface);
  EXPECT_EQ(loops.size(), 2u);
}

// The held-out harder plate: a 380 x 260 mm cut-out with 6 mm corners (perimeter 2 (380 + 260) - 8 r + 2 pi r =
// 1269.7 mm, 0.2% more for the slope) and the seeded smooth field alone (sag, bend, twist and the rigid motion off):
// the truth moves by at most field_mm along z and field_mm / 2 along x and y, by a good part of it somewhere, and
// another seed gives another field.
TEST(Panel, HarderPlateCutOutAndSmoothField) {
  PanelOptions o = harder_plate(PlateOpening::kRoundedRectangle, 3);
  o.scan_points = 2000;
  o.contour_spacing_mm = 1.0;
  o.surface_edge_mm = 4.0;
  o.sag_mm = o.bend_mm = o.twist_mm = 0.0;
  o.rotation_deg.setZero();
  o.translation_mm.setZero();
  const PanelData d = generate_panel(o);
  EXPECT_NEAR(d.perimeter_mm, 1269.7 * 1.002, 3.0);
  Eigen::Vector3d largest = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < d.truth.points.size(); ++i) {
    const Eigen::Vector3d moved = d.truth.points[i] - d.trajectory.points[i];
    largest = largest.cwiseMax(moved.cwiseAbs());
  }
  EXPECT_LE(largest.z(), o.field_mm);
  EXPECT_LE(largest.x(), 0.5 * o.field_mm);
  EXPECT_LE(largest.y(), 0.5 * o.field_mm);
  EXPECT_GT(largest.norm(), 0.2 * o.field_mm);
  PanelOptions other = o;
  other.seed = 4;
  EXPECT_GT((deform_point(other, d.trajectory.points[0]) - d.truth.points[0]).norm(), 1e-3);
  PanelOptions bad = o;
  bad.corner_radius_mm = 200.0;  // more than half the 260 mm side
  EXPECT_THROW(generate_panel(bad), Error);
}

TEST(Panel, ZeroDeformationLeavesTheTruthNominal) {
  PanelOptions o = small(PanelShape::kNoseCone);
  o.ovality_mm = o.droop_mm = 0.0;
  o.rotation_deg.setZero();
  o.translation_mm.setZero();
  o.noise_mm = 0.0;
  const PanelData d = generate_panel(o);
  for (std::size_t i = 0; i < d.truth.points.size(); ++i) {
    EXPECT_LT((d.truth.points[i] - d.trajectory.points[i]).norm(), 1e-12);
    EXPECT_LT((d.truth.normals[i] - d.trajectory.normals[i]).norm(), 1e-9);
  }
  // Without noise the scan lies on the barrel (r = 1000 mm) or on the flank (r in [996, 1000]); float storage.
  for (const pcl::PointXYZ& p : d.scan.points) {
    const double r = std::hypot(static_cast<double>(p.y), static_cast<double>(p.z));
    EXPECT_GE(r, 996.0 - 1e-3);
    EXPECT_LE(r, 1000.0 + 1e-3);
  }
}

TEST(Panel, NoseConeScanNoiseMissingArcsAndDeterminism) {
  PanelOptions o = small(PanelShape::kNoseCone);
  const PanelData full = generate_panel(o);
  EXPECT_EQ(full.scan.size(), 20000u);
  o.missing_fraction = 0.2;
  const PanelData missing = generate_panel(o);
  EXPECT_EQ(missing.missing_arcs.size(), 4u);
  // 20% of the edge's length, over 15 of the band's 40 mm plus the 4 mm flank, of 44 mm in all: 8.6% of the points;
  // +-1.5% for the mesh rows (4 mm) that decide where a missing arc ends across the band.
  EXPECT_NEAR(static_cast<double>(missing.scan_points_removed) / 20000.0, 0.086, 0.015);
  const PanelData again = generate_panel(o);
  ASSERT_EQ(again.scan.size(), missing.scan.size());
  for (std::size_t i = 0; i < again.scan.size(); ++i) EXPECT_EQ(again.scan.points[i].x, missing.scan.points[i].x);
}

// A dent presses into the part at the opening's edge, on the plate (oval and cut-out) and on the nose cone: with every
// other deformation off, the truth's rows move by the dent alone, into the part along the nominal normal, its full
// depth at the row nearest the dent's centre (within 0.5 mm of it: 1 mm rows) and nothing two widths away.
TEST(Panel, DentsPressIntoThePartAtTheEdge) {
  for (const PanelShape shape : {PanelShape::kPlate, PanelShape::kNoseCone}) {
    for (const PlateOpening opening : {PlateOpening::kEllipse, PlateOpening::kRoundedRectangle}) {
      if (shape == PanelShape::kNoseCone && opening == PlateOpening::kRoundedRectangle) continue;
      for (const double at : {0.3, 0.55}) {
        PanelOptions o = small(shape);
        o.opening = opening;
        o.sag_mm = o.bend_mm = o.twist_mm = o.ovality_mm = o.droop_mm = o.field_mm = 0.0;
        o.rotation_deg.setZero();
        o.translation_mm.setZero();
        o.dent_depth_mm = 1.0;
        o.dent_width_mm = 20.0;
        o.dent_at = at;
        const PanelData d = generate_panel(o);
        std::size_t deepest = 0;
        double depth = 0.0;
        for (std::size_t i = 0; i < d.truth.points.size(); ++i) {
          const Eigen::Vector3d move = d.truth.points[i] - d.trajectory.points[i];
          // Into the part: the plate along -z, the nose cone towards the barrel's axis (its nominal normal).
          const Eigen::Vector3d inward =
              shape == PanelShape::kPlate ? Eigen::Vector3d(-Eigen::Vector3d::UnitZ()) : -d.trajectory.normals[i];
          EXPECT_LT((move - move.norm() * inward).norm(), 1e-6 + 1e-3 * move.norm()) << i;
          if (move.norm() > depth) depth = move.norm(), deepest = i;
        }
        const std::string what = std::string(to_string(shape)) + " " + to_string(opening) + " " + std::to_string(at);
        EXPECT_NEAR(depth, 1.0, 0.01) << what;  // the row within 0.5 mm of the centre: exp(-0.5^2 / 50) of it
        for (std::size_t i = 0; i < d.truth.points.size(); ++i) {
          if ((d.trajectory.points[i] - d.trajectory.points[deepest]).norm() > 40.0) {
            EXPECT_LT((d.truth.points[i] - d.trajectory.points[i]).norm(), 1e-6) << what << ", row " << i;
          }
        }
      }
    }
  }
}

// A laser-stripe scan: without deformation and noise every point lies on a plane x = k spacing (float storage) and on
// the nominal surface (where the plane cuts it: a point moved off its face is left out), the plate's and the nose
// cone's, with the points asked less those and the faces the stripes cannot cross (measured: 61-70 % kept).
TEST(Panel, StripeScansLieOnTheirPlanes) {
  for (const PanelShape shape : {PanelShape::kPlate, PanelShape::kNoseCone}) {
    PanelOptions o = small(shape);
    o.sag_mm = o.bend_mm = o.twist_mm = o.ovality_mm = o.droop_mm = 0.0;
    o.rotation_deg.setZero();
    o.translation_mm.setZero();
    o.noise_mm = 0.0;
    o.stripe_spacing_mm = 2.5;
    const PanelData d = generate_panel(o);
    EXPECT_GT(d.scan.size(), 10000u) << to_string(shape);
    const TriangleIndex surface(d.surface);
    for (const pcl::PointXYZ& p : d.scan.points) {
      const double x = static_cast<double>(p.x);
      EXPECT_NEAR(x, 2.5 * std::round(x / 2.5), 1e-3) << to_string(shape);
      const Eigen::Vector3d q(x, static_cast<double>(p.y), static_cast<double>(p.z));
      EXPECT_LT(surface.closest(q).sq_distance, 1e-6) << to_string(shape);
    }
  }
  PanelOptions bad = small(PanelShape::kPlate);
  bad.stripe_spacing_mm = 0.1;
  EXPECT_THROW(generate_panel(bad), Error);
}

// Stripes at an angle: every point on a plane d . p = k spacing, d = (cos a, sin a, 0), and none on the planes across
// x when the angle is not 0 (a wrong turn would leave the points on x = k spacing or off both); 0 deg gives the same
// scan as no angle. Out of [-90, 90] deg: refused.
TEST(Panel, StripesAtAnAngleLieOnTheirPlanes) {
  PanelOptions o = small(PanelShape::kPlate);
  o.sag_mm = o.bend_mm = o.twist_mm = 0.0;
  o.rotation_deg.setZero();
  o.translation_mm.setZero();
  o.noise_mm = 0.0;
  o.stripe_spacing_mm = 3.0;
  const PanelData straight = generate_panel(o);
  for (const double angle : {30.0, -45.0, 90.0}) {
    o.stripe_angle_deg = angle;
    const PanelData d = generate_panel(o);
    EXPECT_GT(d.scan.size(), 10000u) << angle;
    const double a = angle / kDegPerRad;
    std::size_t on_x_planes = 0;
    for (const pcl::PointXYZ& p : d.scan.points) {
      const double s = std::cos(a) * static_cast<double>(p.x) + std::sin(a) * static_cast<double>(p.y);
      EXPECT_NEAR(s, 3.0 * std::round(s / 3.0), 2e-3) << angle;
      const double x = static_cast<double>(p.x);
      if (std::abs(x - 3.0 * std::round(x / 3.0)) < 1e-3) ++on_x_planes;
    }
    EXPECT_LT(on_x_planes, d.scan.size() / 20) << angle;
  }
  o.stripe_angle_deg = 0.0;
  const PanelData again = generate_panel(o);
  ASSERT_EQ(again.scan.size(), straight.scan.size());
  for (std::size_t k = 0; k < again.scan.size(); ++k) EXPECT_EQ(again.scan.points[k].x, straight.scan.points[k].x);
  o.stripe_angle_deg = 91.0;
  EXPECT_THROW(generate_panel(o), Error);
}

// scan_points 0: each shape's default_scan_points (the number `generate plate --help` and `nosecone --help` state).
TEST(Panel, ZeroScanPointsDrawsTheShapesDefault) {
  EXPECT_EQ(default_scan_points(PanelShape::kPlate), 120000);
  EXPECT_EQ(default_scan_points(PanelShape::kNoseCone), 300000);
  PanelOptions o = small(PanelShape::kPlate);
  o.scan_points = 0;
  EXPECT_EQ(static_cast<std::int64_t>(generate_panel(o).scan.size()), default_scan_points(PanelShape::kPlate));
}

TEST(Panel, BadOptionsThrow) {
  PanelOptions o = small(PanelShape::kNoseCone);
  o.corner_radius_mm = 500.0;
  EXPECT_THROW(generate_panel(o), Error);
  o = small(PanelShape::kPlate);
  o.surface_edge_mm = 0.0;
  EXPECT_THROW(generate_panel(o), Error);
  o = small(PanelShape::kPlate);
  o.missing_fraction = 0.95;
  EXPECT_THROW(generate_panel(o), Error);
}

}  // namespace
}  // namespace conform
