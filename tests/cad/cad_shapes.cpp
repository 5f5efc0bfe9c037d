#include "cad_shapes.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopoDS_Compound.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepTools.hxx>
#include <GProp_GProps.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>

#include "conform/core/io.h"
#include "conform/core/mesh.h"

namespace conform::test {

TopoDS_Shape box_with_boss_and_hole() {
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 60.0, 40.0, 20.0).Shape();
  const TopoDS_Shape boss = BRepPrimAPI_MakeBox(gp_Pnt(10, 10, 20), 20.0, 20.0, 10.0).Shape();
  const TopoDS_Shape fused = BRepAlgoAPI_Fuse(block, boss).Shape();
  const TopoDS_Shape drill = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(45, 20, -5), gp::DZ()), 6.0, 40.0).Shape();
  return BRepAlgoAPI_Cut(fused, drill).Shape();
}

TopoDS_Shape flange() {
  TopoDS_Shape shape = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ()), 100.0, 20.0).Shape();
  shape = BRepAlgoAPI_Cut(shape, cylinder(40.0, -5.0, 25.0)).Shape();
  for (int k = 0; k < 6; ++k) {
    const double a = k * M_PI / 3.0;
    const gp_Pnt centre(70.0 * std::cos(a), 70.0 * std::sin(a), -5.0);
    shape = BRepAlgoAPI_Cut(shape, BRepPrimAPI_MakeCylinder(gp_Ax2(centre, gp::DZ()), 8.0, 30.0).Shape()).Shape();
  }
  const TopoDS_Shape keyway = BRepPrimAPI_MakeBox(gp_Pnt(-6.0, 30.0, -5.0), 12.0, 17.0, 30.0).Shape();
  return BRepAlgoAPI_Cut(shape, keyway).Shape();
}

namespace {

// `shape` with a symmetric chamfer of `size_mm` on its edges that run at height z_mm along y = y_mm (both ends).
TopoDS_Shape chamfer_edges_at(const TopoDS_Shape& shape, double y_mm, double z_mm, double size_mm) {
  TopTools_IndexedDataMapOfShapeListOfShape faces_of_edge;
  TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, faces_of_edge);
  BRepFilletAPI_MakeChamfer chamfer(shape);
  for (int i = 1; i <= faces_of_edge.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(faces_of_edge.FindKey(i));
    const gp_Pnt a = BRep_Tool::Pnt(TopExp::FirstVertex(edge)), b = BRep_Tool::Pnt(TopExp::LastVertex(edge));
    if (std::abs(a.Z() - z_mm) < 1e-9 && std::abs(b.Z() - z_mm) < 1e-9 && std::abs(a.Y() - y_mm) < 1e-9 &&
        std::abs(b.Y() - y_mm) < 1e-9) {
      chamfer.Add(size_mm, size_mm, edge, TopoDS::Face(faces_of_edge.FindFromIndex(i).First()));
    }
  }
  return chamfer.Shape();
}

}  // namespace

TopoDS_Shape filleted_block() {
  const TopoDS_Shape block = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 60.0, 40.0, 20.0).Shape();
  BRepFilletAPI_MakeFillet fillet(block);
  // The four vertical edges: both ends at the same x and y.
  for (TopExp_Explorer e(block, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    const gp_Pnt a = BRep_Tool::Pnt(TopExp::FirstVertex(edge)), b = BRep_Tool::Pnt(TopExp::LastVertex(edge));
    if (std::abs(a.X() - b.X()) < 1e-9 && std::abs(a.Y() - b.Y()) < 1e-9) fillet.Add(10.0, edge);
  }
  const TopoDS_Shape rounded = fillet.Shape();
  // The chamfer on the top edge along y = 40; OCCT carries it along the tangent chain, all the way round.
  const TopoDS_Shape chamfered = chamfer_edges_at(rounded, 40.0, 20.0, 4.0);
  const TopoDS_Shape pocket = BRepPrimAPI_MakeBox(gp_Pnt(8, 8, 15), 16.0, 10.0, 10.0).Shape();
  return BRepAlgoAPI_Cut(chamfered, pocket).Shape();
}

TopoDS_Shape ribbed_plate() {
  TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 120.0, 80.0, 10.0).Shape();
  for (int i = 0; i < 3; ++i) {
    part = BRepAlgoAPI_Fuse(part, BRepPrimAPI_MakeBox(gp_Pnt(10.0 + 30.0 * i, 5, 10), 6.0, 70.0, 8.0).Shape()).Shape();
  }
  part = BRepAlgoAPI_Fuse(part, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(100, 40, 10), gp::DZ()), 9.0, 12.0).Shape())
             .Shape();
  part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeBox(gp_Pnt(90, 8, 4), 22.0, 14.0, 10.0).Shape()).Shape();
  return chamfer_edges_at(part, 80.0, 10.0, 3.0);
}

TopoDS_Shape square_plate(bool marked) {
  TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 100.0, 100.0, 10.0).Shape();
  const auto drill = [&](double x, double y, double radius) {
    part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, -5), gp::DZ()), radius, 20.0).Shape())
               .Shape();
  };
  for (const double x : {15.0, 85.0}) {
    for (const double y : {15.0, 85.0}) drill(x, y, 6.0);
  }
  BRepBuilderAPI_MakePolygon corner(gp_Pnt(89, 101, -5), gp_Pnt(101, 101, -5), gp_Pnt(101, 89, -5), Standard_True);
  const TopoDS_Face triangle = BRepBuilderAPI_MakeFace(corner.Wire(), Standard_True).Face();
  part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakePrism(triangle, gp_Vec(0, 0, 20)).Shape()).Shape();
  if (marked) drill(50.0, 25.0, 10.0);
  return part;
}

TopoDS_Shape long_profile(bool unique) {
  TopoDS_Shape part = BRepAlgoAPI_Fuse(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 2000.0, 12.0, 200.0).Shape(),
                                       BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 188), 2000.0, 80.0, 12.0).Shape())
                          .Shape();
  const auto drill = [&](const gp_Pnt& from, const gp_Dir& along, double radius) {
    part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeCylinder(gp_Ax2(from, along), radius, 30.0).Shape()).Shape();
  };
  const std::vector<double> holes =
      unique ? std::vector<double>{250, 700, 1250, 1750} : std::vector<double>{250, 750, 1250, 1750};
  const std::vector<double> scallops =
      unique ? std::vector<double>{500, 960, 1500} : std::vector<double>{500, 1000, 1500};
  for (const double x : holes) drill(gp_Pnt(x, -5, 90), gp::DY(), 30.0);
  for (const double x : scallops) drill(gp_Pnt(x, -5, 0), gp::DY(), 25.0);
  if (unique) drill(gp_Pnt(850, 30, 180), gp::DZ(), 9.0);
  return part;
}

namespace {

// The triangle (x, y0, z0), (x, y1, z1), (x, y2, z2) in the plane x = x0, extruded by `length_mm` along +x.
TopoDS_Shape triangular_prism(double x0, const double (&yz)[3][2], double length_mm) {
  BRepBuilderAPI_MakePolygon outline(gp_Pnt(x0, yz[0][0], yz[0][1]), gp_Pnt(x0, yz[1][0], yz[1][1]),
                                     gp_Pnt(x0, yz[2][0], yz[2][1]), Standard_True);
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(outline.Wire(), Standard_True).Face();
  return BRepPrimAPI_MakePrism(face, gp_Vec(length_mm, 0, 0)).Shape();
}

}  // namespace

TopoDS_Shape welded_bracket() {
  TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 120.0, 80.0, 10.0).Shape();
  part = BRepAlgoAPI_Fuse(part, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 10), 120.0, 10.0, 80.0).Shape()).Shape();
  const double gusset[3][2] = {{10, 10}, {60, 10}, {10, 60}};
  for (const double x : {20.0, 92.0}) part = BRepAlgoAPI_Fuse(part, triangular_prism(x, gusset, 8.0)).Shape();
  const double weld[3][2] = {{10, 10}, {16, 10}, {10, 16}};
  part = BRepAlgoAPI_Fuse(part, triangular_prism(0.0, weld, 120.0)).Shape();
  for (const double x : {30.0, 90.0}) {
    part = BRepAlgoAPI_Cut(part, BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, 55, -5), gp::DZ()), 6.0, 20.0).Shape())
               .Shape();
  }
  return part;
}

TopoDS_Shape thin_plates(double thickness) {
  const double t = thickness;
  TopoDS_Shape part = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), 120.0, 80.0, t).Shape();
  part = BRepAlgoAPI_Fuse(part, BRepPrimAPI_MakeBox(gp_Pnt(0, 0, t), 120.0, t, 70.0 - t).Shape()).Shape();
  part = BRepAlgoAPI_Fuse(part, BRepPrimAPI_MakeBox(gp_Pnt(25, t, t), t, 60.0 - t, 50.0 - t).Shape()).Shape();
  return BRepAlgoAPI_Fuse(part, BRepPrimAPI_MakeBox(gp_Pnt(80, t, t), t, 40.0 - t, 30.0 - t).Shape()).Shape();
}

TopoDS_Shape cylinder() { return BRepPrimAPI_MakeCylinder(gp_Ax2(gp::Origin(), gp::DZ()), 15.0, 40.0).Shape(); }

TopoDS_Shape filleted_cylinder() {
  const TopoDS_Shape c = cylinder();
  BRepFilletAPI_MakeFillet fillet(c);
  // The top edge: the circle at z = 40 (the seam runs along z).
  for (TopExp_Explorer e(c, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    const gp_Pnt a = BRep_Tool::Pnt(TopExp::FirstVertex(edge)), b = BRep_Tool::Pnt(TopExp::LastVertex(edge));
    if (std::abs(a.Z() - 40.0) < 1e-9 && std::abs(b.Z() - 40.0) < 1e-9) fillet.Add(3.0, edge);
  }
  return fillet.Shape();
}

TopoDS_Shape cylinder(double radius_mm, double z0_mm, double z1_mm) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, z0_mm), gp::DZ()), radius_mm, z1_mm - z0_mm).Shape();
}

TopoDS_Shape drill_split_hole(const TopoDS_Shape& part, double x_mm, double y_mm, double radius_mm, double z0_mm,
                              double z1_mm) {
  TopoDS_Shape out = part;
  // A half cylinder spans the angle pi from its x direction about z: from +x the half y >= y_mm, from -x the other.
  for (const gp_Dir& start : {gp_Dir(1, 0, 0), gp_Dir(-1, 0, 0)}) {
    const gp_Ax2 axes(gp_Pnt(x_mm, y_mm, z0_mm), gp::DZ(), start);
    out = BRepAlgoAPI_Cut(out, BRepPrimAPI_MakeCylinder(axes, radius_mm, z1_mm - z0_mm, M_PI).Shape()).Shape();
  }
  return out;
}

TopoDS_Shape faces_of_triangles(const std::vector<Eigen::Vector3d>& vertices,
                                const std::vector<std::array<std::int32_t, 3>>& triangles) {
  TopoDS_Compound compound;
  BRep_Builder builder;
  builder.MakeCompound(compound);
  const auto point = [&](std::int32_t i) {
    const Eigen::Vector3d& v = vertices[static_cast<std::size_t>(i)];
    return gp_Pnt(v.x(), v.y(), v.z());
  };
  for (const auto& t : triangles) {
    BRepBuilderAPI_MakePolygon wire(point(t[0]), point(t[1]), point(t[2]), Standard_True);
    BRepBuilderAPI_MakeFace face(wire.Wire(), Standard_True);
    if (!face.IsDone()) throw std::runtime_error("faces_of_triangles: a triangle without area");
    builder.Add(compound, face.Face());
  }
  return compound;
}

TopoDS_Shape torus() { return BRepPrimAPI_MakeTorus(gp_Ax2(gp::Origin(), gp::DZ()), 10.0, 3.0).Shape(); }

void write_scan(const std::string& path, const std::vector<Eigen::Vector3d>& points) {
  Mesh cloud;
  cloud.vertices = points;
  WriteOptions precise;
  precise.double_precision = true;
  write_mesh(path, cloud, precise);
}

void write_cad(const TopoDS_Shape& shape, const std::string& path, CadFormat format, const std::string& unit) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  bool ok = false;
  if (format == CadFormat::kStep) {
    STEPControl_Controller::Init();  // registers write.step.unit: setting it before is silently ignored
    Interface_Static::SetCVal("write.step.unit", unit.c_str());
    STEPControl_Writer writer;
    ok = writer.Transfer(shape, STEPControl_AsIs) == IFSelect_RetDone && writer.Write(path.c_str()) == IFSelect_RetDone;
  } else {
    IGESControl_Controller::Init();
    IGESControl_Writer writer(unit.c_str(), 1);  // BRep mode: solids stay solids
    ok = writer.AddShape(shape) && (writer.ComputeModel(), writer.Write(path.c_str()));
  }
  if (!ok) throw std::runtime_error("could not write " + path);
}

SurfaceSample sample_surface(const TopoDS_Shape& shape, std::size_t count, double sigma_mm, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> noise(0.0, sigma_mm > 0.0 ? sigma_mm : 1.0);
  GProp_GProps total;
  BRepGProp::SurfaceProperties(shape, total);
  SurfaceSample out;
  int face_index = -1;
  for (TopExp_Explorer e(shape, TopAbs_FACE); e.More(); e.Next()) {
    ++face_index;
    const TopoDS_Face& face = TopoDS::Face(e.Current());
    GProp_GProps props;
    BRepGProp::SurfaceProperties(face, props);
    const auto wanted = static_cast<std::size_t>(std::lround(static_cast<double>(count) * props.Mass() / total.Mass()));
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    std::uniform_real_distribution<double> u_of(u0, u1), v_of(v0, v1);
    const BRepAdaptor_Surface surface(face);
    // The face's wires as polygons in (u, v), built once (a point near them is classified exactly): the classifier
    // per point took 60 us on faces with many holes (a 2 m profile, 250 000 points: 16 s).
    const BRepTopAdaptor_FClass2d classifier(face, 1e-9);
    for (std::size_t got = 0, tries = 0; got < wanted && tries < 100 * wanted; ++tries) {
      const double u = u_of(random), v = v_of(random);
      if (classifier.Perform(gp_Pnt2d(u, v)) != TopAbs_IN) continue;
      BRepLProp_SLProps props_at(surface, u, v, 1, 1e-9);
      if (!props_at.IsNormalDefined()) continue;
      gp_Dir n = props_at.Normal();
      if (face.Orientation() == TopAbs_REVERSED) n.Reverse();
      const gp_Pnt p = props_at.Value();
      const Eigen::Vector3d normal(n.X(), n.Y(), n.Z());
      const double offset = sigma_mm > 0.0 ? noise(random) : 0.0;
      out.points.push_back(Eigen::Vector3d(p.X(), p.Y(), p.Z()) + offset * normal);
      out.normals.push_back(normal);
      out.offset_mm.push_back(offset);
      out.face.push_back(face_index);
      ++got;
    }
  }
  return out;
}

}  // namespace conform::test
