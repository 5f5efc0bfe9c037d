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

class PointListRoundTrip : public ::testing::TestWithParam<const char*> {};

// Tolerance: none. A float cloud's shortest text reads back as the same floats.
TEST_P(PointListRoundTrip, CloudWithAndWithoutNormals) {
  test::TempDir dir;
  const std::string path = dir.file(std::string("c") + GetParam());
  for (bool normals : {false, true}) {
    const Cloud cloud = test::random_cloud(500, normals);
    write_cloud(path, cloud);
    test::expect_same_cloud(read_cloud(path), cloud);
  }
}

// Tolerance: none; 17 significant digits (shortest round-trip text of the double) give the doubles back.
TEST_P(PointListRoundTrip, DoublePrecisionGivesTheDoublesBack) {
  test::TempDir dir;
  const std::string path = dir.file(std::string("m") + GetParam());
  Mesh mesh = test::grid_mesh(5, 5, true);
  mesh.faces.clear();
  write_mesh(path, mesh, {Encoding::kAscii, true});
  test::expect_same_mesh(read_geometry(path), mesh, test::Stored::kDouble);
  write_mesh(path, mesh);
  test::expect_same_mesh(read_geometry(path), mesh, test::Stored::kFloatText);
}

TEST_P(PointListRoundTrip, SameCloudGivesSameBytes) {
  test::TempDir dir;
  const Cloud cloud = test::random_cloud(50, true);
  write_cloud(dir.file(std::string("a") + GetParam()), cloud);
  write_cloud(dir.file(std::string("b") + GetParam()), cloud);
  EXPECT_EQ(read_bytes(dir.file(std::string("a") + GetParam())), read_bytes(dir.file(std::string("b") + GetParam())));
}

INSTANTIATE_TEST_SUITE_P(PointList, PointListRoundTrip, ::testing::Values(".xyz", ".csv", ".txt", ".asc"));

TEST(PointList, HeaderLinesAreTheDocumentedOnes) {
  test::TempDir dir;
  Cloud cloud;
  cloud.points.push_back({1.5f, -2.0f, 0.1f});
  cloud.normals.push_back({0.0f, 0.0f, 1.0f});
  write_cloud(dir.file("c.csv"), cloud);
  EXPECT_EQ(read_bytes(dir.file("c.csv")), "x,y,z,nx,ny,nz\n1.5,-2,0.1,0,0,1\n");
  write_cloud(dir.file("c.xyz"), cloud);
  EXPECT_EQ(read_bytes(dir.file("c.xyz")), "# x y z nx ny nz\n1.5 -2 0.1 0 0 1\n");
}

TEST(PointList, CsvWithHeaderInAnyOrder) {
  test::TempDir dir;
  write_bytes(dir.file("h.csv"),
              "\"Intensity\";\"Z\";\"X\";\"Y\";Normal_X;Normal_Y;Normal_Z\r\n"
              "17; 3.5 ;1;2;0;0;1\r\n"
              "\r\n"
              "18;-1e-3;4;5;1;0;0\r\n");
  const Mesh mesh = read_geometry(dir.file("h.csv"));
  ASSERT_EQ(mesh.vertices.size(), 2u);
  EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(1, 2, 3.5));
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(4, 5, -1e-3));
  EXPECT_EQ(mesh.normals[1], Eigen::Vector3d(1, 0, 0));
}

TEST(PointList, NoHeaderFirstThreeColumnsAndCommentsSkipped) {
  test::TempDir dir;
  write_bytes(dir.file("p.xyz"),
              "// exported by a scanner, x y z in mm\n"
              "# scan 3\n"
              "1 2 3 255 0 0\n"
              "\n"
              "\t4   5\t6 7\n"
              "# a comment in between\n"
              "+7 8e0 .5\n");
  const Mesh mesh = read_geometry(dir.file("p.xyz"));
  ASSERT_EQ(mesh.vertices.size(), 3u);
  EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(7, 8, 0.5));
  EXPECT_FALSE(mesh.has_normals());
}

TEST(PointList, CommentHeaderNamesColumns) {
  test::TempDir dir;
  write_bytes(dir.file("p.txt"), "# nx ny nz x y z\n0 0 1 10 20 30\n");
  const Mesh mesh = read_geometry(dir.file("p.txt"));
  EXPECT_EQ(mesh.vertices.at(0), Eigen::Vector3d(10, 20, 30));
  EXPECT_EQ(mesh.normals.at(0), Eigen::Vector3d(0, 0, 1));
}

TEST(PointList, NonNumericTokenGivesLineAndColumn) {
  test::TempDir dir;
  write_bytes(dir.file("p.xyz"), "1 2 3\n4 5 6\n7 eight 9\n");
  EXPECT_EQ(error_of([&] { read_cloud(dir.file("p.xyz")); }),
            dir.file("p.xyz") + ":3: column 2: 'eight' is not a number");
  write_bytes(dir.file("p.csv"), "x,y,z\n1,2,3\n1,,3\n");
  EXPECT_EQ(error_of([&] { read_cloud(dir.file("p.csv")); }), dir.file("p.csv") + ":3: column 2: '' is not a number");
  write_bytes(dir.file("q.csv"), "1,2,3\n4,5,1e999\n");
  EXPECT_EQ(error_of([&] { read_cloud(dir.file("q.csv")); }),
            dir.file("q.csv") + ":2: column 3: '1e999' is out of range");
}

TEST(PointList, SemicolonsTakePrecedenceOverDecimalCommas) {
  test::TempDir dir;
  write_bytes(dir.file("p.csv"), "1;2;3\n1,5;2;3\n");
  EXPECT_EQ(error_of([&] { read_cloud(dir.file("p.csv")); }),
            dir.file("p.csv") + ":2: column 1: '1,5' is not a number");
}

TEST(PointList, HeaderWithoutXyzAndShortLinesAreErrors) {
  test::TempDir dir;
  write_bytes(dir.file("a.csv"), "a,b,c\n1,2,3\n");
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("a.csv")); }),
                  dir.file("a.csv") + ":1: column 1: 'a' is not a number (nor is the line a header naming x, y, z)");
  write_bytes(dir.file("b.xyz"), "1 2 3\n4 5\n");
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("b.xyz")); }),
                  dir.file("b.xyz") + ":2: expected at least 3 columns, found 2");
  write_bytes(dir.file("c.csv"), "x,y,z,nx,ny,nz\n1,2,3,0,0\n");
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("c.csv")); }), ":2: expected at least 6 columns, found 5");
}

TEST(PointList, MeshWithFacesIsNotWrittenAsPoints) {
  test::TempDir dir;
  EXPECT_CONTAINS(error_of([&] { write_mesh(dir.file("m.xyz"), test::grid_mesh(1, 1, false)); }),
                  dir.file("m.xyz") + ": .xyz files hold points only: writing the mesh would lose its 2 faces");
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
