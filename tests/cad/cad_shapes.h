#pragma once
// CAD made in the test with OpenCASCADE itself (issue 22): the shapes, written as STEP or IGES in a chosen unit, and
// scans sampled on their exact surfaces with a known normal offset (the noise), so that a deviation computed
// against the tessellated reference can be compared with the offset point by point.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

class TopoDS_Shape;

namespace conform::test {

// A 60 x 40 x 20 mm block at the origin with a 20 x 20 x 10 mm boss on top at (10..30, 10..30) and a through hole
// of diameter 12 mm along z at (45, 20): 13 faces; inside the hole is outside the part.
TopoDS_Shape box_with_boss_and_hole();
// A 60 x 40 x 20 mm block at the origin whose four vertical edges are rounded with R10 fillets (tangent: the flat
// sides meet the fillets without a crease), a 4 mm 45-degree chamfer round the top's rim (put on the edge along
// y = 40, it follows the tangent fillets all the way round: the top's corners are arcs of R6) and a 16 x 10 mm pocket
// 5 mm deep in the top at (8..24, 8..18): flat faces next to fillets and steps, as machined.
TopoDS_Shape filleted_block();
// A flange (z up, its axis the z axis): a disc of radius 100 mm, 20 mm thick, a 40 mm bore, six 8 mm bolt holes on a
// 70 mm circle at 0, 60, ..., 300 deg and one keyway, 12 mm wide and 7 mm deep, in the bore at 90 deg: six-fold
// symmetric but for the keyway.
TopoDS_Shape flange();
// A machined plate 120 x 80 x 10 mm: three ribs 6 x 70 x 8 mm on top at x = 10, 40, 70, a boss of R9 and 12 mm at
// (100, 40), a pocket 22 x 14 mm, 6 mm deep, at (90..112, 8..22), and a 3 mm chamfer on the top edge along y = 80.
TopoDS_Shape ribbed_plate();
// A square plate 100 x 100 x 10 mm (z up) with four 12 mm holes at 15 mm from its corners and a 45-degree chamfer
// cutting its vertical edge at (100, 100) back to x + y = 190: a half turn about its diagonal x = y (through the
// plate's middle) maps it onto itself, its top onto its bottom. `marked`: one more hole, R10 at (50, 25), off the
// diagonal, so that it is not symmetric.
TopoDS_Shape square_plate(bool marked);
// An L-profile 2000 mm long along x: a web 12 mm thick (y 0..12) and 200 mm high (z), a flange 80 x 12 mm on its top
// (y 0..80, z 188..200). Through the web, R30 holes at z = 90 and R25 scallops at its toe (z = 0). `unique`: holes at
// x = 250, 700, 1250, 1750, scallops at 500, 960, 1500 and an R9 pin hole through the flange at (850, 30), so that
// each stretch of 500 mm is told apart from another; else holes every 500 mm from 250 and scallops every 500 mm from
// 500, so that a stretch clear of the ends fits as well 500 mm along.
TopoDS_Shape long_profile(bool unique);
// A welded bracket: a base plate 120 x 80 x 10 mm (z up), an upright plate 120 x 10 x 80 mm on it along y = 0..10,
// two gussets 8 mm thick at x = 20 and x = 92 (right triangles of 50 mm legs in the corner between the plates), a
// fillet weld with 6 mm legs along the inside corner, and two 12 mm holes through the base at (30, 55) and (90, 55).
TopoDS_Shape welded_bracket();
// A part of thin plates, all `thickness` mm: a base 120 x 80 (z up), an upright 70 mm tall along y = 0..t, and two ribs
// at x = 25 and x = 80 reaching y = 60 and 40, z = 50 and 30 (tests/registration/plates_part.h as CAD).
TopoDS_Shape thin_plates(double thickness);
// Radius 15 mm, height 40 mm, axis z from the origin.
TopoDS_Shape cylinder();
// The same cylinder with its top edge rounded by an R3 fillet: a cylinder face meeting a torus without a crease, the
// side tessellated as strips the cylinder's whole height.
TopoDS_Shape filleted_cylinder();
// Major radius 10 mm, minor 3 mm, about z (small: a torus face is the slowest to tessellate).
TopoDS_Shape torus();
// A solid cylinder of radius r along z from z0 to z1.
TopoDS_Shape cylinder(double radius_mm, double z0_mm, double z1_mm);
// `part` with a hole of radius r along z through (x, y), from z0 to z1, cut as two half cylinders (the halves
// y >= y_mm and y <= y_mm of the hole): its wall is two cylindrical faces on one cylinder, as many CAD kernels and
// STEP exporters split a full cylinder.
TopoDS_Shape drill_split_hole(const TopoDS_Shape& part, double x_mm, double y_mm, double radius_mm, double z0_mm,
                              double z1_mm);
// Every triangle a planar face of its own, in one compound (free faces, wound as the triangles): a mesh as CAD, whose
// tessellation gives back the same triangles.
TopoDS_Shape faces_of_triangles(const std::vector<Eigen::Vector3d>& vertices,
                                const std::vector<std::array<std::int32_t, 3>>& triangles);

// The points as a cloud .ply in double precision (the scan's coordinates to the last bit).
void write_scan(const std::string& path, const std::vector<Eigen::Vector3d>& points);

enum class CadFormat { kStep, kIges };
// unit: "MM" or "M" (the file's coordinates are then in metres).
void write_cad(const TopoDS_Shape& shape, const std::string& path, CadFormat format, const std::string& unit);

struct SurfaceSample {
  std::vector<Eigen::Vector3d> points;   // on the exact surface, moved along the outward normal by offset_mm
  std::vector<Eigen::Vector3d> normals;  // outward unit normals of the exact surface
  std::vector<double> offset_mm;         // the signed normal offset of each point (outside positive)
  std::vector<int> face;                 // the index of its face in the shape's face order (TopExp_Explorer)
};

// About `count` points over the shape's faces (in proportion to their areas), each offset by a Gaussian of
// `sigma_mm` along the outward normal, from a generator seeded with `seed`.
SurfaceSample sample_surface(const TopoDS_Shape& shape, std::size_t count, double sigma_mm, std::uint64_t seed);

}  // namespace conform::test
