// The CAD reference face by face (issue 33, core/cad_faces.h): each triangle's B-rep face and each face's surface type,
// nominal parameters and outside, through the plugin's C interface and the child's pipe, against CAD made here with
// OpenCASCADE and points sampled on its exact faces.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <TopoDS_Shape.hxx>

#include "cad_shapes.h"
#include "conform/core/cad_faces.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::CadFormat;

CadFaces read_faces(const TopoDS_Shape& shape, const test::TempDir& dir, const std::string& name, CadFormat format,
                    const std::string& unit, CadReport* report) {
  const std::string path = dir.file(name);
  test::write_cad(shape, path, format, unit);
  return read_cad_faces(path, CadReadOptions{}, report, nullptr);
}

std::map<std::string, int> type_counts(const CadFaces& cad) {
  std::map<std::string, int> counts;
  for (const CadFace& f : cad.faces) ++counts[to_string(f.type)];
  return counts;
}

Eigen::Vector3d triangle_normal(const Mesh& mesh, std::size_t t) {
  const Face& f = mesh.faces[t];
  const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(f[0])];
  const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(f[1])];
  const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(f[2])];
  return (b - a).cross(c - a).normalized();
}

// Every triangle lies on its face's analytic surface within the deflection, wound to its outside: its corners within
// the deflection of the exact surface and its normal within `max_angle_deg` of the surface's outward normal at its
// centroid (the chord of a curved face turns by up to the angular deflection, 11.5 deg at the default).
void expect_triangles_on_their_faces(const CadFaces& cad, double max_angle_deg) {
  ASSERT_EQ(cad.triangle_face.size(), cad.mesh.faces.size());
  const double deflection_mm = CadReadOptions{}.deflection_mm;
  std::size_t checked = 0;
  for (std::size_t t = 0; t < cad.mesh.faces.size(); ++t) {
    const CadFace& face = cad.faces[static_cast<std::size_t>(cad.triangle_face[t])];
    if (!is_analytic(face.type)) continue;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (const std::int32_t v : cad.mesh.faces[t]) {
      const Eigen::Vector3d& p = cad.mesh.vertices[static_cast<std::size_t>(v)];
      EXPECT_LT(std::abs(analytic_signed_distance(face, p)), 1e-6) << "triangle " << t << " " << to_string(face.type);
      centroid += p / 3.0;
    }
    EXPECT_LE(-analytic_signed_distance(face, centroid), deflection_mm * 1.001) << t;  // the chord lies inside
    const double cosine = triangle_normal(cad.mesh, t).dot(analytic_outward_normal(face, centroid));
    EXPECT_GT(cosine, std::cos(max_angle_deg * M_PI / 180.0)) << "triangle " << t << " " << to_string(face.type);
    ++checked;
  }
  EXPECT_GT(checked, 0u);
}

// Points sampled on each exact face, offset along its outward normal by Gaussian noise: the distance to the face's
// nominal surface is that offset to 1e-9 mm, so origin, axis, radii and the outside are all exact.
void expect_offsets_are_the_analytic_distance(const TopoDS_Shape& shape, const CadFaces& cad) {
  const test::SurfaceSample scan = test::sample_surface(shape, 3000, 0.05, 11);
  ASSERT_GT(scan.points.size(), 2500u);
  std::size_t checked = 0;
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    ASSERT_LT(static_cast<std::size_t>(scan.face[i]), cad.faces.size());
    const CadFace& face = cad.faces[static_cast<std::size_t>(scan.face[i])];
    if (!is_analytic(face.type)) continue;
    EXPECT_NEAR(analytic_signed_distance(face, scan.points[i]), scan.offset_mm[i], 1e-9)
        << "face " << scan.face[i] << " " << to_string(face.type);
    EXPECT_GT(analytic_outward_normal(face, scan.points[i]).dot(scan.normals[i]), 1.0 - 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, scan.points.size() / 2);
}

TEST(CadFaces, BlockWithBossAndHoleInMillimetresAndMetres) {
  test::TempDir dir;
  const TopoDS_Shape shape = test::box_with_boss_and_hole();
  for (const char* unit : {"MM", "M"}) {
    for (const CadFormat format : {CadFormat::kStep, CadFormat::kIges}) {
      SCOPED_TRACE(std::string(unit) + (format == CadFormat::kStep ? " STEP" : " IGES"));
      CadReport report;
      const CadFaces cad = read_faces(shape, dir, format == CadFormat::kStep ? "b.step" : "b.igs", format, unit,
                                      &report);
      ASSERT_EQ(cad.faces.size(), report.faces);
      const std::map<std::string, int> counts = type_counts(cad);
      EXPECT_EQ(counts.at("plane"), static_cast<int>(cad.faces.size()) - 1);
      ASSERT_EQ(counts.at("cylinder"), 1);
      std::size_t triangles = 0;
      for (const CadFace& f : cad.faces) {
        triangles += f.triangles;
        if (f.type == CadSurfaceType::kPlane) {
          // Axis-aligned outward normals: the largest component is +-1 to 1e-12.
          EXPECT_NEAR(f.axis.cwiseAbs().maxCoeff(), 1.0, 1e-12);
          if (std::abs(f.centre_mm.z()) < 1e-9) {
            EXPECT_NEAR(f.axis.z(), -1.0, 1e-12);  // the base
          }
        }
        if (f.type != CadSurfaceType::kCylinder) continue;
        EXPECT_NEAR(f.radius_mm, 6.0, 6.0 * 1e-9);
        EXPECT_NEAR(std::abs(f.axis.z()), 1.0, 1e-9);
        EXPECT_NEAR(f.origin_mm.x(), 45.0, 45.0 * 1e-9);
        EXPECT_NEAR(f.origin_mm.y(), 20.0, 20.0 * 1e-9);
        EXPECT_NEAR(f.origin_mm.z(), 10.0, 1e-6);  // the axis point at the face's middle (the hole is 0..20)
        EXPECT_EQ(f.sense, -1);                    // a hole: outside is towards the axis
        EXPECT_NEAR(f.area_mm2, 2.0 * M_PI * 6.0 * 20.0, 1e-6);
      }
      EXPECT_EQ(triangles, cad.mesh.faces.size());
      EXPECT_EQ(cad.mesh.faces.size(), report.triangles);
      expect_triangles_on_their_faces(cad, 12.0);
      if (format == CadFormat::kStep) expect_offsets_are_the_analytic_distance(shape, cad);
    }
  }
}

TEST(CadFaces, CylinderTorusAndFlangeHaveTheirNominalRadiiAndOutside) {
  test::TempDir dir;
  CadReport report;
  const CadFaces cylinder = read_faces(test::cylinder(), dir, "c.igs", CadFormat::kIges, "M", &report);
  EXPECT_EQ(type_counts(cylinder), (std::map<std::string, int>{{"cylinder", 1}, {"plane", 2}}));
  for (const CadFace& f : cylinder.faces) {
    if (f.type == CadSurfaceType::kPlane) {
      EXPECT_NEAR(std::abs(f.axis.z()), 1.0, 1e-12);
      EXPECT_EQ(f.axis.z() > 0.0, f.centre_mm.z() > 20.0);  // the top up, the bottom down
    }
    if (f.type != CadSurfaceType::kCylinder) continue;
    EXPECT_NEAR(f.radius_mm, 15.0, 15.0 * 1e-9);
    EXPECT_NEAR(f.origin_mm.head<2>().norm(), 0.0, 1e-9);
    EXPECT_EQ(f.sense, 1);
  }
  expect_triangles_on_their_faces(cylinder, 12.0);

  const TopoDS_Shape torus = test::torus();
  const CadFaces t = read_faces(torus, dir, "t.step", CadFormat::kStep, "MM", &report);
  ASSERT_EQ(t.faces.size(), 1u);
  EXPECT_EQ(t.faces[0].type, CadSurfaceType::kTorus);
  EXPECT_NEAR(t.faces[0].radius_mm, 10.0, 1e-8);
  EXPECT_NEAR(t.faces[0].minor_radius_mm, 3.0, 3e-9);
  EXPECT_EQ(t.faces[0].sense, 1);
  expect_triangles_on_their_faces(t, 12.0);
  expect_offsets_are_the_analytic_distance(torus, t);

  const TopoDS_Shape flange = test::flange();
  const CadFaces f = read_faces(flange, dir, "f.step", CadFormat::kStep, "MM", &report);
  int bolt_holes = 0, bores = 0, rims = 0;
  for (const CadFace& face : f.faces) {
    if (face.type != CadSurfaceType::kCylinder) continue;
    const double at_mm = face.origin_mm.head<2>().norm();
    if (std::abs(face.radius_mm - 8.0) < 8e-9 && std::abs(at_mm - 70.0) < 1e-9) {
      ++bolt_holes;
      EXPECT_EQ(face.sense, -1);
    } else if (std::abs(face.radius_mm - 40.0) < 4e-8 && at_mm < 1e-9) {
      ++bores;
      EXPECT_EQ(face.sense, -1);
    } else if (std::abs(face.radius_mm - 100.0) < 1e-7 && at_mm < 1e-9) {
      ++rims;
      EXPECT_EQ(face.sense, 1);
    }
  }
  EXPECT_EQ(bolt_holes, 6);
  EXPECT_GE(bores, 1);  // the bore, cut by the keyway
  EXPECT_EQ(rims, 1);
  expect_triangles_on_their_faces(f, 12.0);
  expect_offsets_are_the_analytic_distance(flange, f);
}

// Fillets are cylinders (a boss-like outside), the chamfer round the tangent corners cones of 45 deg.
TEST(CadFaces, FilletedBlockHasCylindersAndCones) {
  test::TempDir dir;
  CadReport report;
  const TopoDS_Shape shape = test::filleted_block();
  const CadFaces cad = read_faces(shape, dir, "fb.step", CadFormat::kStep, "MM", &report);
  EXPECT_EQ(type_counts(cad), (std::map<std::string, int>{{"cone", 4}, {"cylinder", 4}, {"plane", 15}}));
  int fillets = 0;
  for (const CadFace& f : cad.faces) {
    if (f.type == CadSurfaceType::kCylinder && std::abs(f.radius_mm - 10.0) < 1e-8) {
      ++fillets;
      EXPECT_EQ(f.sense, 1);
      EXPECT_NEAR(std::abs(f.axis.z()), 1.0, 1e-12);
    }
    if (f.type == CadSurfaceType::kCone) {
      EXPECT_NEAR(f.half_angle_rad, M_PI / 4.0, 1e-9);
    }
  }
  EXPECT_EQ(fillets, 4);
  expect_triangles_on_their_faces(cad, 12.0);
  expect_offsets_are_the_analytic_distance(shape, cad);
}

}  // namespace
}  // namespace conform
