// `conform inspect` on cones and tori: the least-squares cone's half-angle and axis, the least-squares torus's radii
// and centre, and their form (the zone of the residuals about the fitted surface, 1 % trimmed) against generated
// ground truth. Each made surface differs from its CAD face by size and position errors (which the fit takes up) and
// a three-lobed waviness of 0.01 mm amplitude round the axis (which it cannot: cos 3 theta is orthogonal to every
// change of a surface of revolution's parameters over the full turn), plus Gaussian noise of 0.005 mm. The true form
// is the 1 %-trimmed zone of the waviness plus the noise of the very points scanned. Three seeds each.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <BRepPrimAPI_MakeCone.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>

#include "cad_shapes.h"
#include "conform/core/cad_faces.h"
#include "conform/core/random.h"
#include "conform/core/constants.h"
#include "conform/pipelines/inspect/inspect.h"
#include "inspect_scans.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

constexpr double kNoise = 0.005, kWave = 0.01;
const std::uint64_t kSeeds[] = {4, 19, 37};

// The share-trimmed zone of v (the trim_share / 2 and 1 - trim_share / 2 quantiles, linear between ranks).
double trimmed_zone(std::vector<double> v, double trim_share) {
  std::sort(v.begin(), v.end());
  const auto quantile = [&](double q) {
    const double at = q * static_cast<double>(v.size() - 1);
    const auto i = static_cast<std::size_t>(std::floor(at));
    const std::size_t j = std::min(i + 1, v.size() - 1);
    return v[i] + (at - static_cast<double>(i)) * (v[j] - v[i]);
  };
  return quantile(1.0 - 0.5 * trim_share) - quantile(0.5 * trim_share);
}

double theta_of(const Eigen::Vector3d& p) { return std::atan2(p.y(), p.x()); }

// A frustum, R 20 at z = 0 to R 10 at z = 20: its apex at z = 40, half-angle atan(1/2) = 26.565 deg. As made: the
// half-angle 0.05 deg larger about the same apex height, the axis moved (0.03, -0.02) mm; the cone scanned in the
// band 3 < z < 17 (the rims unseen), the end discs in full.
TEST(InspectRevolved, ConeHalfAngleAxisAndForm) {
  test::TempDir dir;
  const TopoDS_Shape cone = BRepPrimAPI_MakeCone(gp_Ax2(gp::Origin(), gp::DZ()), 20.0, 10.0, 20.0).Shape();
  const std::string step = dir.file("cone.step");
  const CadFaces cad = test::write_step(cone, step);
  std::size_t cone_face = cad.faces.size();
  for (std::size_t f = 0; f < cad.faces.size(); ++f) {
    if (cad.faces[f].type == CadSurfaceType::kCone) cone_face = f;
  }
  ASSERT_LT(cone_face, cad.faces.size());
  const CadFace& nominal = cad.faces[cone_face];
  ASSERT_NEAR(degrees(nominal.half_angle_rad), degrees(std::atan(0.5)), 1e-9);
  ASSERT_LT((nominal.origin_mm - Eigen::Vector3d(0, 0, 40)).norm(), 1e-9);

  const double made_angle = nominal.half_angle_rad + radians(0.05);
  const Eigen::Vector3d made_apex(0.03, -0.02, 40.0), u(0, 0, -1);  // the axis from the apex into the cone
  // The signed distance of p from the made cone, + away from its axis: rho cos a - h sin a.
  const auto made_distance = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - made_apex;
    const double h = d.dot(u), rho = (d - h * u).norm();
    return rho * std::cos(made_angle) - h * std::sin(made_angle);
  };
  for (const std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const test::SurfaceSample s = test::sample_surface(cone, 20000, 0.0, seed);
    Random random(seed + 50);
    std::vector<Eigen::Vector3d> points;
    std::vector<double> form_truth;  // the waviness and noise of each cone point: what is left about the made cone
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d& p = s.points[i];
      if (static_cast<std::size_t>(s.face[i]) != cone_face) {
        points.push_back(p + kNoise * random.normal() * s.normals[i]);
        continue;
      }
      if (p.z() < 3.0 || p.z() > 17.0) continue;
      const double form = kWave * std::cos(3.0 * theta_of(p)) + kNoise * random.normal();
      points.push_back(p + (form - made_distance(p)) * s.normals[i]);
      form_truth.push_back(form);
    }
    test::write_scan(dir.file("scan.ply"), points);
    const InspectResult r = test::inspect_in_part_frame(dir.file("scan.ply"), step);
    ASSERT_TRUE(r.ok) << r.termination;
    const FaceInspection& f = r.faces[cone_face];
    ASSERT_TRUE(f.fitted) << f.fit_note;
    EXPECT_EQ(f.form_reference, "least-squares cone");
    EXPECT_GE(f.points, static_cast<std::size_t>(0.95 * static_cast<double>(form_truth.size())));
    EXPECT_NEAR(f.half_angle_deg, degrees(made_angle), 0.003);
    EXPECT_LT(f.axis_angle_deg, 0.01);
    EXPECT_NEAR(f.axis_offset_mm, std::hypot(0.03, 0.02), 0.003);
    // The radius at the face's middle section: the made cone's there.
    const double h_middle = (nominal.centre_mm - made_apex).dot(u);
    EXPECT_NEAR(f.radius_mm, h_middle * std::tan(made_angle), 0.003);
    EXPECT_NEAR(f.nominal_radius_mm, h_middle * std::tan(nominal.half_angle_rad), 1e-9);
    // The form: the waviness and the noise, not the size and position errors (0.03-0.04 mm here).
    const double truth = trimmed_zone(form_truth, f.form.trim_share);
    EXPECT_NEAR(f.form.width_mm, truth, 0.001);
    EXPECT_GT(f.form.width_mm, 2.0 * kWave);
  }
}

// A torus R 10 / r 3 about z (one face). As made: the major radius 0.03 mm larger, the minor 0.02 mm smaller, the
// centre moved (0.02, -0.01, 0.015) mm; scanned from above (z > -1: a little over the upper half of the tube).
TEST(InspectRevolved, TorusRadiiCentreAndForm) {
  test::TempDir dir;
  const TopoDS_Shape torus = test::torus();
  const std::string step = dir.file("torus.step");
  const CadFaces cad = test::write_step(torus, step);
  ASSERT_EQ(cad.faces.size(), 1u);
  ASSERT_EQ(cad.faces[0].type, CadSurfaceType::kTorus);
  const Eigen::Vector3d made_centre(0.02, -0.01, 0.015);
  const double made_major = 10.03, made_minor = 2.98;
  // The signed distance of p from the made torus, + away from the tube's centre circle.
  const auto made_distance = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d d = p - made_centre;
    return std::hypot(d.head<2>().norm() - made_major, d.z()) - made_minor;
  };
  for (const std::uint64_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const test::SurfaceSample s = test::sample_surface(torus, 20000, 0.0, seed);
    Random random(seed + 60);
    std::vector<Eigen::Vector3d> points;
    std::vector<double> form_truth;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const Eigen::Vector3d& p = s.points[i];
      if (p.z() < -1.0) continue;
      const double form = kWave * std::cos(3.0 * theta_of(p)) + kNoise * random.normal();
      points.push_back(p + (form - made_distance(p)) * s.normals[i]);
      form_truth.push_back(form);
    }
    test::write_scan(dir.file("scan.ply"), points);
    const InspectResult r = test::inspect_in_part_frame(dir.file("scan.ply"), step);
    ASSERT_TRUE(r.ok) << r.termination;
    const FaceInspection& f = r.faces[0];
    ASSERT_TRUE(f.fitted) << f.fit_note;
    EXPECT_EQ(f.form_reference, "least-squares torus");
    EXPECT_NEAR(f.radius_mm, made_major, 0.003);
    EXPECT_NEAR(f.minor_radius_mm, made_minor, 0.003);
    EXPECT_NEAR(f.centre_offset_mm, made_centre.norm(), 0.003);
    EXPECT_LT((f.centre_mm - made_centre).norm(), 0.003);
    EXPECT_LT(f.axis_angle_deg, 0.01);
    const double truth = trimmed_zone(form_truth, f.form.trim_share);
    EXPECT_NEAR(f.form.width_mm, truth, 0.001);
    EXPECT_GT(f.form.width_mm, 2.0 * kWave);
  }
  // The CLI's text and the faces' CSV give the fitted torus (the last seed's scan).
  const test::RunResult run = test::run(CONFORM_EXE, {"inspect", "--scan", dir.file("scan.ply"), "--reference", step,
                                                      "--out-faces", dir.file("faces.csv")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("radii 10.030"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("(nominal 10.0000 / 3.0000)"), std::string::npos) << run.out;
  const std::string csv = test::read_bytes(dir.file("faces.csv"));
  const std::size_t row = csv.find("\n1,torus,");
  ASSERT_NE(row, std::string::npos) << csv;
  EXPECT_NE(csv.find(",least-squares torus,10.0", row), std::string::npos) << csv;  // form reference, major radius
}

}  // namespace
}  // namespace conform
