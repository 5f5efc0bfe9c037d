// What io.h does whatever the format: choosing the format by extension, the NonFinitePolicy, the errors for
// files that are missing, empty or of an unknown kind, and atomic writing.

#include "conform/core/io.h"

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "io_test_data.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::error_of;
using test::read_bytes;
using test::write_bytes;

TEST(FileExtension, LowerCaseWithTheDot) {
  EXPECT_EQ(file_extension("scan.PLY"), ".ply");
  EXPECT_EQ(file_extension("/data/v1.2/part.tar.Gz"), ".gz");
  EXPECT_EQ(file_extension("/data/v1.2/README"), "");
  EXPECT_EQ(file_extension("dir/.ply"), "");
  EXPECT_EQ(file_extension("noext"), "");
}

TEST(Io, UnknownExtensionNamesTheFileAndTheSupportedOnes) {
  test::TempDir dir;
  write_bytes(dir.file("scan.e57"), "anything");
  const std::string message = error_of([&] { read_cloud(dir.file("scan.e57")); });
  EXPECT_CONTAINS(message, dir.file("scan.e57") + ": unknown file extension '.e57'");
  EXPECT_CONTAINS(message, ".ply .stl .obj .pcd .xyz .txt .asc .csv");
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("scan")); }), "no file extension");
  EXPECT_CONTAINS(error_of([&] { write_cloud(dir.file("out.las"), Cloud()); }), "unknown file extension '.las'");
}

TEST(Io, MissingFileNamesItAndTheReason) {
  for (const char* name :
       {"/nonexistent/a.ply", "/nonexistent/a.stl", "/nonexistent/a.obj", "/nonexistent/a.pcd", "/nonexistent/a.xyz"}) {
    EXPECT_EQ(error_of([&] { read_geometry(name); }), std::string(name) + ": cannot open (No such file or directory)");
  }
}

TEST(Io, EmptyFileIsAnErrorInEveryFormat) {
  test::TempDir dir;
  for (const char* name : {"e.ply", "e.stl", "e.obj", "e.pcd", "e.xyz", "e.csv", "e.txt", "e.asc"}) {
    write_bytes(dir.file(name), "");
    EXPECT_EQ(error_of([&] { read_geometry(dir.file(name)); }), dir.file(name) + ": is empty");
  }
  EXPECT_CONTAINS(error_of([&] { read_geometry(dir.path() + "/"); }), "no file extension");
}

TEST(Io, ReadMeshWantsFaces) {
  test::TempDir dir;
  write_cloud(dir.file("c.ply"), test::random_cloud(5, false));
  EXPECT_EQ(error_of([&] { read_mesh(dir.file("c.ply")); }),
            dir.file("c.ply") + ": holds no faces (5 points only), but a mesh is needed here");
}

// Vertex 1 and vertex 3 are not finite; faces 0 and 1 use vertex 1, face 2 uses vertex 3, face 3 uses neither.
void write_mesh_with_non_finite(const std::string& path) {
  write_bytes(path,
              "ply\nformat ascii 1.0\nelement vertex 6\nproperty double x\nproperty double y\nproperty double z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
              "0 0 0 0 0 1\nnan 0 0 0 0 1\n1 0 0 0 0 1\n1 inf 0 0 0 1\n0 1 0 0 0 1\n2 2 2 0 1 0\n"
              "3 0 1 2\n3 1 2 4\n3 0 3 4\n3 0 2 4\n");
}

TEST(Io, NonFiniteVerticesAreRejectedByDefault) {
  test::TempDir dir;
  write_mesh_with_non_finite(dir.file("n.ply"));
  EXPECT_EQ(error_of([&] { read_mesh(dir.file("n.ply")); }),
            dir.file("n.ply") + ": 2 vertices have a NaN or infinite coordinate (the first is vertex 1)");
}

TEST(Io, DropRemovesNonFiniteVerticesAndTheirFacesAndReindexes) {
  test::TempDir dir;
  write_mesh_with_non_finite(dir.file("n.ply"));
  ReadReport report;
  const Mesh mesh = read_mesh(dir.file("n.ply"), {NonFinitePolicy::kDrop}, &report);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(2, 2, 2));
  EXPECT_EQ(mesh.normals.size(), 4u);
  EXPECT_EQ(mesh.normals[3], Eigen::Vector3d(0, 1, 0));
  ASSERT_EQ(mesh.faces.size(), 1u);
  EXPECT_EQ(mesh.faces[0], (Face{0, 1, 2}));  // was 0 2 4
  EXPECT_EQ(report.non_finite_points, 2u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0], dir.file("n.ply") +
                                    ": dropped 2 vertices with a NaN or infinite coordinate (the first was vertex 1)"
                                    " and the 3 faces that used them");
}

TEST(Io, KeepKeepsThemAndCounts) {
  test::TempDir dir;
  write_mesh_with_non_finite(dir.file("n.ply"));
  ReadReport report;
  const Mesh mesh = read_mesh(dir.file("n.ply"), {NonFinitePolicy::kKeep}, &report);
  EXPECT_EQ(mesh.vertices.size(), 6u);
  EXPECT_EQ(mesh.faces.size(), 4u);
  EXPECT_TRUE(std::isnan(mesh.vertices[1].x()));
  EXPECT_EQ(report.non_finite_points, 2u);
  EXPECT_TRUE(report.warnings.empty());
}

TEST(Io, NonFinitePointsInEveryFormat) {
  test::TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Cloud cloud = test::random_cloud(4, false);
  cloud.points[2].y = nan;
  Mesh mesh = test::grid_mesh(1, 1, false);
  mesh.vertices[3].z() = -std::numeric_limits<double>::infinity();
  for (const char* name : {"c.ply", "c.pcd", "c.xyz", "c.csv", "c.obj"}) {
    write_cloud(dir.file(name), cloud);
    EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file(name)); }), "(the first is vertex 2)");
    EXPECT_EQ(read_cloud(dir.file(name), {NonFinitePolicy::kDrop}).size(), 3u) << name;
  }
  for (const char* name : {"m.ply", "m.stl", "m.obj"}) {
    write_mesh(dir.file(name), mesh);
    EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file(name)); }), "1 vertex has a NaN or infinite coordinate");
    EXPECT_EQ(read_geometry(dir.file(name), {NonFinitePolicy::kDrop}).faces.size(), 0u) << name;  // both used it
  }
}

TEST(Io, FailedWriteLeavesNothingAndKeepsTheOldFile) {
  test::TempDir dir;
  write_bytes(dir.file("m.ply"), "old");
  Mesh broken = test::grid_mesh(1, 1, false);
  broken.faces[1][2] = 9;
  EXPECT_CONTAINS(error_of([&] { write_mesh(dir.file("m.ply"), broken); }), "face 1 refers to vertex 9");
  EXPECT_EQ(read_bytes(dir.file("m.ply")), "old");
  EXPECT_EQ(dir.listing(), "m.ply\n");
  EXPECT_CONTAINS(error_of([&] { write_mesh("/nonexistent-dir/m.ply", test::grid_mesh(1, 1, false)); }),
                  "/nonexistent-dir/m.ply: cannot open for writing");
}

TEST(Io, WritingReplacesAnExistingFile) {
  test::TempDir dir;
  write_bytes(dir.file("m.stl"), std::string(1000, 'x'));
  const Mesh mesh = test::grid_mesh(2, 2, false);
  write_mesh(dir.file("m.stl"), mesh);
  EXPECT_EQ(read_mesh(dir.file("m.stl")).faces.size(), mesh.faces.size());
  EXPECT_EQ(dir.listing(), "m.stl\n");
}

}  // namespace
}  // namespace conform
