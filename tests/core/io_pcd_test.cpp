#include <cstdint>
#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "io_test_data.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::error_of;
using test::read_bytes;
using test::write_bytes;

struct PcdCase {
  Encoding encoding;
  bool normals;
};

class PcdRoundTrip : public ::testing::TestWithParam<PcdCase> {};

// Tolerance: none (binary stores the floats; ascii prints 9 significant digits, enough for any float).
TEST_P(PcdRoundTrip, CloudComesBackExactly) {
  test::TempDir dir;
  const Cloud cloud = test::random_cloud(400, GetParam().normals);
  write_cloud(dir.file("c.pcd"), cloud, {GetParam().encoding, false});
  test::expect_same_cloud(read_cloud(dir.file("c.pcd")), cloud);
  EXPECT_EQ(dir.listing(), "c.pcd\n");
}

TEST_P(PcdRoundTrip, SameCloudGivesSameBytes) {
  test::TempDir dir;
  const Cloud cloud = test::random_cloud(100, GetParam().normals);
  write_cloud(dir.file("a.pcd"), cloud, {GetParam().encoding, false});
  write_cloud(dir.file("b.pcd"), cloud, {GetParam().encoding, false});
  EXPECT_EQ(read_bytes(dir.file("a.pcd")), read_bytes(dir.file("b.pcd")));
}

TEST_P(PcdRoundTrip, EmptyCloud) {
  test::TempDir dir;
  Cloud cloud;
  write_cloud(dir.file("e.pcd"), cloud, {GetParam().encoding, false});
  EXPECT_TRUE(read_cloud(dir.file("e.pcd")).empty());
}

INSTANTIATE_TEST_SUITE_P(Pcd, PcdRoundTrip,
                         ::testing::Values(PcdCase{Encoding::kBinary, false}, PcdCase{Encoding::kBinary, true},
                                           PcdCase{Encoding::kAscii, false}, PcdCase{Encoding::kAscii, true}));

TEST(Pcd, ReadsWhatPclWritesIncludingPaddingAndNormals) {
  test::TempDir dir;
  pcl::PointCloud<pcl::PointNormal> points;
  points.push_back(pcl::PointNormal(1.5f, 2.5f, -3.0f, 0.0f, 1.0f, 0.0f, 0.25f));
  points.push_back(pcl::PointNormal(4.0f, 5.0f, 6.0f, 1.0f, 0.0f, 0.0f, 0.5f));
  ASSERT_EQ(pcl::io::savePCDFileBinary(dir.file("p.pcd"), points), 0);
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(dir.file("z.pcd"), points), 0);
  for (const char* name : {"p.pcd", "z.pcd"}) {
    testing::internal::CaptureStderr();
    const Cloud cloud = read_cloud(dir.file(name));
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    ASSERT_EQ(cloud.size(), 2u);
    EXPECT_EQ(cloud.points[1].getVector3fMap(), Eigen::Vector3f(4, 5, 6));
    EXPECT_EQ(cloud.normals[0].getNormalVector3fMap(), Eigen::Vector3f(0, 1, 0));
  }
}

std::string pcd_header(const std::string& points, const std::string& data, const std::string& fields = "x y z",
                       const std::string& sizes = "4 4 4", const std::string& types = "F F F") {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types +
         "\nCOUNT 1 1 1\nWIDTH " + points + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data +
         "\n";
}

TEST(Pcd, DoubleAndIntegerCoordinatesAreConverted) {
  test::TempDir dir;
  write_bytes(dir.file("d.pcd"), pcd_header("2", "ascii", "x y z", "8 8 2", "F F I") + "0.1 0.2 -3\n1 2 7\n");
  const Mesh mesh = read_geometry(dir.file("d.pcd"));
  ASSERT_EQ(mesh.vertices.size(), 2u);
  EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(0.1, 0.2, -3));
}

// Each of these is a conform::Error naming the file (and the line), with nothing printed. (PCL 1.13's own reader,
// which conform used before, allocated what the header claims, crashed without FIELDS and read bad values as 0.)
TEST(Pcd, MalformedFilesAreErrorsAndPclStaysQuiet) {
  test::TempDir dir;
  std::string body;
  for (int i = 0; i < 10; ++i) {
    const float xyz[3] = {static_cast<float>(i), 2.0f, 3.0f};
    body.append(reinterpret_cast<const char*>(xyz), sizeof(xyz));
  }
  const struct {
    std::string bytes;
    std::string expected;
  } cases[] = {
      {pcd_header("10", "binary") + body.substr(0, 50), "claims 10 points (120 bytes) but 50 bytes follow the DATA line"},
      {pcd_header("100000000", "binary") + body, "claims 100000000 points (1200000000 bytes)"},
      {pcd_header("4000000000", "binary") + body, "more than 2147483647 points"},
      {pcd_header("2", "ascii") + "1 2 3\n   \n", "claims 2 points but the file holds 1"},
      {pcd_header("1", "ascii") + "1\v2 3\n", ":12: field 'x' (TYPE F SIZE 4): '1\v2' is not a number"},
      {"VERSION 0.7\nSIZE 4 4 4\nFIELDS x y z\n", ":2: SIZE must come once, after FIELDS"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nVIEWPOINT 0 0 0 1 0 0\n", ":4: VIEWPOINT must have 7 values"},
      {pcd_header("100", "ascii") + "1 2 3\n4 5 6\n", "claims 100 points (at least 6 bytes each)"},
      {pcd_header("4", "ascii") + "1.000 2.000 3.000\n4.000 5.000 6.000\n",
       "claims 4 points but the file holds 2"},
      {pcd_header("2", "ascii") + "1 2 3\n4 abc 6\n", ":13: field 'y' (TYPE F SIZE 4): 'abc' is not a number"},
      {pcd_header("2", "ascii") + "1 2 3\n4 5\n", ":13: expected 3 values, found 2"},
      {pcd_header("1", "ascii") + "1 2 3\n4 5 6\n", ":13: more points than the header's 1"},
      {"VERSION 0.7\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA binary\n", ":5: the PCD header has no FIELDS"},
      {pcd_header("1", "binary", "a b c") + body, "the PCD file has no 'x' field"},
      {pcd_header("2", "binary_compressed") + std::string(8, '\0'), "compressed PCD data holds 0 bytes"},
      {"# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n", "PCD header has no DATA line"},
      {"# .PCD v0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n",
       ":8: WIDTH x HEIGHT (2 x 2) is not POINTS (3)"},
  };
  for (const auto& c : cases) {
    write_bytes(dir.file("bad.pcd"), c.bytes);
    testing::internal::CaptureStderr();
    testing::internal::CaptureStdout();
    const std::string message = error_of([&] { read_cloud(dir.file("bad.pcd")); });
    const std::string printed = testing::internal::GetCapturedStderr() + testing::internal::GetCapturedStdout();
    EXPECT_CONTAINS(message, dir.file("bad.pcd"));
    EXPECT_CONTAINS(message, c.expected);
    EXPECT_EQ(printed, "");
  }
}

TEST(Pcd, DamagedCompressedDataAndUnwritablePlacesAreQuietErrors) {
  test::TempDir dir;
  pcl::PointCloud<pcl::PointXYZ> points;
  for (int i = 0; i < 1000; ++i) points.push_back(pcl::PointXYZ(static_cast<float>(i), 1.0f, 2.0f));
  ASSERT_EQ(pcl::io::savePCDFileBinaryCompressed(dir.file("z.pcd"), points), 0);
  std::string bytes = read_bytes(dir.file("z.pcd"));
  const std::size_t payload = bytes.find("DATA binary_compressed\n") + 23 + 8;
  for (std::size_t i = payload; i < bytes.size(); i += 7) bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
  write_bytes(dir.file("z.pcd"), bytes);
  testing::internal::CaptureStderr();
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("z.pcd")); }), "the compressed PCD data is damaged");
  EXPECT_CONTAINS(error_of([&] { write_cloud("/nonexistent-dir/c.pcd", test::random_cloud(3, false)); }),
                  "/nonexistent-dir/c.pcd: cannot open for writing (No such file or directory)");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(Pcd, NanPointsOfAnOrganisedCloudFollowThePolicy) {
  test::TempDir dir;
  write_bytes(dir.file("n.pcd"),
              "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
              "WIDTH 2\nHEIGHT 2\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 4\nDATA ascii\n"
              "1 2 3\nnan nan nan\n4 5 6\n7 8 9\n");
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("n.pcd")); }), "(the first is vertex 1)");
  ReadReport report;
  const Cloud cloud = read_cloud(dir.file("n.pcd"), {NonFinitePolicy::kDrop}, &report);
  ASSERT_EQ(cloud.size(), 3u);
  EXPECT_EQ(cloud.points[1].getVector3fMap(), Eigen::Vector3f(4, 5, 6));
  EXPECT_EQ(report.non_finite_points, 1u);
}

TEST(Pcd, MeshWithFacesIsNotWrittenAsPoints) {
  test::TempDir dir;
  EXPECT_CONTAINS(error_of([&] { write_mesh(dir.file("m.pcd"), test::grid_mesh(2, 1, false)); }),
                  "would lose its 4 faces");
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
