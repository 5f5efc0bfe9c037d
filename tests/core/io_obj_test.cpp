#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "io_test_data.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::error_of;
using test::read_bytes;
using test::write_bytes;

std::string joined(const ReadReport& report) {
  std::string all;
  for (const std::string& w : report.warnings) all += w + "\n";
  return all;
}

// Tolerance: none; shortest float text gives the float back, 17-digit text the double.
TEST(Obj, MeshRoundTripWithAndWithoutNormals) {
  test::TempDir dir;
  for (bool normals : {false, true}) {
    for (bool double_precision : {false, true}) {
      const Mesh mesh = test::grid_mesh(6, 4, normals);
      write_mesh(dir.file("m.obj"), mesh, {Encoding::kAscii, double_precision});
      ReadReport report;
      test::expect_same_mesh(read_mesh(dir.file("m.obj"), {}, &report), mesh,
                             double_precision ? test::Stored::kDouble : test::Stored::kFloatText);
      EXPECT_EQ(joined(report), "");
    }
  }
}

TEST(Obj, CloudRoundTripMapsNormalsInOrder) {
  test::TempDir dir;
  const Cloud cloud = test::random_cloud(200, true);
  write_cloud(dir.file("c.obj"), cloud);
  test::expect_same_cloud(read_cloud(dir.file("c.obj")), cloud);
}

TEST(Obj, SameMeshGivesSameBytes) {
  test::TempDir dir;
  const Mesh mesh = test::grid_mesh(3, 3, true);
  write_mesh(dir.file("a.obj"), mesh);
  write_mesh(dir.file("b.obj"), mesh);
  EXPECT_EQ(read_bytes(dir.file("a.obj")), read_bytes(dir.file("b.obj")));
  EXPECT_CONTAINS(read_bytes(dir.file("a.obj")), "\nf 1//1 2//2 6//6\n");
}

TEST(Obj, TextureAndNormalIndicesNegativeIndicesAndAQuad) {
  test::TempDir dir;
  write_bytes(dir.file("h.obj"),
              "# a unit square\n"
              "mtllib part.mtl\n"
              "o square\n"
              "v 0 0 0\n"
              "v 1 0 0 1.0\n"
              "v 1 1 0\n"
              "v 0 1 0 0.5 0.5 0.5\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
              "vn 0 0 1\n"
              "g top\nusemtl steel\ns off\n"
              "f -4/1/1 -3/2/1 -2/3/1 -1/4/1\n"
              "v 2 0 0\n"
              "f 2//1 5//1 3//-1\n"
              "l 1 2\n");
  ReadReport report;
  const Mesh mesh = read_mesh(dir.file("h.obj"), {}, &report);
  ASSERT_EQ(mesh.vertices.size(), 5u);
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 1, 0));
  ASSERT_EQ(mesh.faces.size(), 3u);
  EXPECT_EQ(mesh.faces[0], (Face{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1], (Face{0, 2, 3}));
  EXPECT_EQ(mesh.faces[2], (Face{1, 4, 2}));
  ASSERT_EQ(mesh.normals.size(), 5u);  // every vertex has the one normal
  EXPECT_EQ(mesh.normals[4], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(joined(report), "");
}

TEST(Obj, InconsistentNormalsAreDroppedWithAWarning) {
  test::TempDir dir;
  write_bytes(dir.file("n.obj"),
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nvn 0 0 -1\nf 1//1 2//1 3//1\n"
              "f 2//2 4//2 3//2\n");
  ReadReport report;
  const Mesh mesh = read_mesh(dir.file("n.obj"), {}, &report);
  EXPECT_FALSE(mesh.has_normals());
  EXPECT_CONTAINS(joined(report), "vertex normals dropped: vertex 2 has different normals");
}

TEST(Obj, ErrorsGiveTheLine) {
  test::TempDir dir;
  write_bytes(dir.file("a.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("a.obj")); }),
                  dir.file("a.obj") + ":4: face refers to vertex 4 but 3 vertices are defined so far");
  write_bytes(dir.file("b.obj"), "v 0 0 0\nv 1 0 0\nf -3 1 2\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("b.obj")); }), ":3: face refers to vertex -3");
  write_bytes(dir.file("c.obj"), "# x\nv 0 0 0\nv 1 1,5 0\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("c.obj")); }),
                  dir.file("c.obj") + ":3: column 3: '1,5' is not a number");
  write_bytes(dir.file("d.obj"), "v 0 0\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("d.obj")); }), ":1: expected 3 coordinates, found 2");
  write_bytes(dir.file("e.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("e.obj")); }), ":4: face refers to vertex 0");
}

}  // namespace
}  // namespace conform
