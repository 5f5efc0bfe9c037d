// A STEP file of solids that overlap (two parts never united): their faces inside each other are measured as surfaces
// of the part, so the reader says so, naming the file and the pair; solids that only touch, or lie apart, do not.

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Ax2.hxx>

#include "cad_shapes.h"
#include "conform/core/cad.h"
#include "temp_dir.h"

namespace conform {
namespace {

TopoDS_Shape compound(const std::vector<TopoDS_Shape>& shapes) {
  BRep_Builder builder;
  TopoDS_Compound c;
  builder.MakeCompound(c);
  for (const TopoDS_Shape& s : shapes) builder.Add(c, s);
  return c;
}

std::vector<std::string> overlap_warnings(const TopoDS_Shape& shape, const std::string& path) {
  test::write_cad(shape, path, test::CadFormat::kStep, "MM");
  std::vector<std::string> warnings, out;
  CadReport report;
  read_cad(path, CadReadOptions{}, &report, &warnings);
  for (const std::string& w : warnings) {
    if (w.find("overlap") != std::string::npos) out.push_back(w);
  }
  return out;
}

// Two blocks 60 x 40 x 20 and 20 x 40 x 20 mm sharing 10 mm (the exploration's overlap.step: 39 signs flipped near
// the faces inside); a cylinder pushed 3 mm into a block; the same blocks side by side (touching) and apart.
TEST(CadOverlap, OverlappingSolidsAreNamed) {
  test::TempDir dir;
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 60, 40, 20).Shape();
  const std::string path = dir.file("parts.step");
  const std::vector<std::string> boxes =
      overlap_warnings(compound({a, BRepPrimAPI_MakeBox(gp_Pnt(50, 0, 0), 20, 40, 20).Shape()}), path);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_NE(boxes[0].find(path), std::string::npos) << boxes[0];
  EXPECT_NE(boxes[0].find("solids 1 and 2 overlap"), std::string::npos) << boxes[0];
  const TopoDS_Shape pin = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(30, 20, 17), gp::DZ()), 5, 10).Shape();
  EXPECT_EQ(overlap_warnings(compound({a, pin}), path).size(), 1u);
  const TopoDS_Shape touching = BRepPrimAPI_MakeBox(gp_Pnt(60, 0, 0), 20, 40, 20).Shape();
  EXPECT_TRUE(overlap_warnings(compound({a, touching}), path).empty());
  const TopoDS_Shape on_top = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(30, 20, 20), gp::DZ()), 5, 10).Shape();
  EXPECT_TRUE(overlap_warnings(compound({a, on_top}), path).empty());
  const TopoDS_Shape apart = BRepPrimAPI_MakeBox(gp_Pnt(70, 0, 0), 20, 40, 20).Shape();
  EXPECT_TRUE(overlap_warnings(compound({a, apart}), path).empty());
}

}  // namespace
}  // namespace conform
