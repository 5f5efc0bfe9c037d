// Reading a STEP part of ~1,000 faces: conform's read_mesh (core's check, the plugin loaded with dlopen, OCCT's
// reader, BRepMesh, the orientation check, the weld) against the same OCCT calls made directly (STEPControl_Reader
// + BRepMesh_IncrementalMesh, no copy out): the ratio is what conform adds. Also the STL of the same tessellation
// through conform's STL reader, what users did before (tessellate elsewhere, read the mesh). Best of 3, wall clock.
// The part: perforated_plates() below, 1178 faces.

#include <cstdio>
#include <string>

#include <BRepAlgoAPI_Cut.hxx>
#include <BRep_Builder.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS_Compound.hxx>
#include <unistd.h>

#include "bench_timer.h"
#include "conform/core/io.h"

namespace {

// 31 plates of 100 x 1000 x 20 mm side by side, each with 32 through holes of 8 mm diameter (their positions
// differ from plate to plate, so no two plates share a shape): 31 solids, 31 x 38 = 1178 faces.
TopoDS_Shape perforated_plates() {
  TopoDS_Compound plates;
  BRep_Builder builder;
  builder.MakeCompound(plates);
  for (int i = 0; i < 31; ++i) {
    const double x0 = 110.0 * i;
    TopTools_ListOfShape arguments, tools;
    arguments.Append(BRepPrimAPI_MakeBox(gp_Pnt(x0, 0, 0), 100.0, 1000.0, 20.0).Shape());
    for (int j = 0; j < 32; ++j) {
      const gp_Ax2 axis(gp_Pnt(x0 + 20.0 + 2.0 * (i % 20), 15.0 + 30.5 * j, -5.0), gp::DZ());
      tools.Append(BRepPrimAPI_MakeCylinder(axis, 4.0, 30.0).Shape());
    }
    BRepAlgoAPI_Cut cut;
    cut.SetArguments(arguments);
    cut.SetTools(tools);
    cut.Build();
    builder.Add(plates, cut.Shape());
  }
  return plates;
}

}  // namespace

int main() {
  using conform::bench::best_seconds;
  Message::DefaultMessenger()->ChangePrinters().Clear();
  char dir_template[] = "/tmp/conform-cad-bench-XXXXXX";
  const std::string dir = mkdtemp(dir_template);
  const std::string step = dir + "/plate.step", stl = dir + "/plate.stl";
  const TopoDS_Shape part = perforated_plates();
  int faces = 0;
  for (TopExp_Explorer e(part, TopAbs_FACE); e.More(); e.Next()) ++faces;
  STEPControl_Writer writer;
  writer.Transfer(part, STEPControl_AsIs);
  writer.Write(step.c_str());

  for (const double deflection : {0.05, 0.005}) {
    conform::ReadOptions options;
    options.cad.deflection_mm = deflection;
    conform::Mesh mesh;
    const double ours = best_seconds(3, [&] { mesh = conform::read_mesh(step, options); });
    const double occt = best_seconds(3, [&] {
      STEPControl_Reader reader;
      reader.ReadFile(step.c_str());
      reader.TransferRoots();
      IMeshTools_Parameters parameters;
      parameters.Deflection = deflection;
      parameters.Angle = options.cad.angular_deflection();
      BRepMesh_IncrementalMesh mesher(reader.OneShape(), parameters);
    });
    conform::write_mesh(stl, mesh);
    const double from_stl = best_seconds(3, [&] { conform::read_mesh(stl); });
    std::printf("%d faces, deflection %g mm: %zu triangles; conform %.3f s, OCCT direct %.3f s (conform / OCCT %.2f); "
                "the STL of it %.3f s\n",
                faces, deflection, mesh.faces.size(), ours, occt, ours / occt, from_stl);
  }
  std::remove(step.c_str());
  std::remove(stl.c_str());
  rmdir(dir.c_str());
  return 0;
}
