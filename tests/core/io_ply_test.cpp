#include <cstdint>
#include <cstring>
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

struct PlyCase {
  Encoding encoding;
  bool double_precision;
  bool normals;
};

class PlyRoundTrip : public ::testing::TestWithParam<PlyCase> {};

// Tolerance: none; float files give the vertices rounded to float (ascii too: a float property is read as a
// float), double files give them back exactly.
TEST_P(PlyRoundTrip, MeshComesBackAsWritten) {
  const PlyCase c = GetParam();
  test::TempDir dir;
  const Mesh mesh = test::grid_mesh(7, 5, c.normals);
  write_mesh(dir.file("m.ply"), mesh, {c.encoding, c.double_precision});
  ReadReport report;
  const Mesh back = read_mesh(dir.file("m.ply"), {}, &report);
  test::expect_same_mesh(back, mesh, c.double_precision ? test::Stored::kDouble : test::Stored::kFloat);
  EXPECT_TRUE(report.warnings.empty()) << report.warnings.front();
  EXPECT_EQ(dir.listing(), "m.ply\n");  // no temporary left behind
}

TEST_P(PlyRoundTrip, CloudComesBackExactly) {
  const PlyCase c = GetParam();
  test::TempDir dir;
  const Cloud cloud = test::random_cloud(300, c.normals);
  write_cloud(dir.file("c.ply"), cloud, {c.encoding, c.double_precision});
  test::expect_same_cloud(read_cloud(dir.file("c.ply")), cloud);
  EXPECT_FALSE(read_geometry(dir.file("c.ply")).has_faces());
}

TEST_P(PlyRoundTrip, SameMeshGivesSameBytes) {
  const PlyCase c = GetParam();
  test::TempDir dir;
  const Mesh mesh = test::grid_mesh(4, 3, c.normals);
  write_mesh(dir.file("a.ply"), mesh, {c.encoding, c.double_precision});
  write_mesh(dir.file("b.ply"), mesh, {c.encoding, c.double_precision});
  EXPECT_EQ(read_bytes(dir.file("a.ply")), read_bytes(dir.file("b.ply")));
}

INSTANTIATE_TEST_SUITE_P(
    Ply, PlyRoundTrip,
    ::testing::Values(PlyCase{Encoding::kBinary, false, false}, PlyCase{Encoding::kBinary, false, true},
                      PlyCase{Encoding::kBinary, true, true}, PlyCase{Encoding::kAscii, false, false},
                      PlyCase{Encoding::kAscii, false, true}, PlyCase{Encoding::kAscii, true, true}));

TEST(Ply, BinaryHeaderIsTheDocumentedOne) {
  test::TempDir dir;
  write_mesh(dir.file("m.ply"), test::grid_mesh(1, 1, true));
  const std::string bytes = read_bytes(dir.file("m.ply"));
  const std::string header =
      "ply\nformat binary_little_endian 1.0\ncomment written by conform\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
      "property float nz\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  EXPECT_EQ(bytes.size(), header.size() + 4 * 24 + 2 * 13);
}

TEST(Ply, AsciiWithExtraPropertiesListsElementsAndAQuad) {
  test::TempDir dir;
  write_bytes(dir.file("q.ply"),
              "ply\r\n"
              "format ascii 1.0\n"
              "comment made by hand\n"
              "element vertex 4\n"
              "property uchar red\n"
              "property double x\n"
              "property list uchar int tags\n"
              "property float y\n"
              "property float z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              "element face 2\n"
              "property list uchar uint vertex_indices\n"
              "property int flags\n"
              "element edge 1\n"
              "property int vertex1\nproperty int vertex2\n"
              "end_header\n"
              "255 0 0 0 0 0 0 1\n"
              "7 1.5 2 8 9 0 0 0 0 1\n"
              "1 1.5 0 2.25 0 0 0 1\n"
              "2 +0 1 5 2.25 -1e1 0 0 1\n"
              "4 0 1 2 3 42\n"
              "2 0 1 9\n"
              "0 1\n");
  ReadReport report;
  const Mesh mesh = read_mesh(dir.file("q.ply"), {}, &report);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(1.5, 0, 0));
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(1.5, 2.25, 0));
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 2.25, -10));
  EXPECT_EQ(mesh.normals[3], Eigen::Vector3d(0, 0, 1));
  // The quad is fanned into two triangles; the two-vertex face is skipped with a warning.
  ASSERT_EQ(mesh.faces.size(), 2u);
  EXPECT_EQ(mesh.faces[0], (Face{0, 1, 2}));
  EXPECT_EQ(mesh.faces[1], (Face{0, 2, 3}));
  std::string warnings;
  for (const std::string& w : report.warnings) warnings += w + "\n";
  EXPECT_CONTAINS(warnings, "skipped 1 faces with fewer than 3 vertices");
  EXPECT_CONTAINS(warnings, "red, tags");
  EXPECT_CONTAINS(warnings, "edge");
}

// Big-endian values, written byte by byte.
template <typename T>
void put_be(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) out += bytes[sizeof(T) - 1 - i];
}

TEST(Ply, BigEndianWithDoubleVerticesAndShortIndices) {
  test::TempDir dir;
  std::string bytes =
      "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nproperty short confidence\nelement face 1\nproperty list int ushort vertex_index\n"
      "end_header\n";
  const double xyz[3][3] = {{0.1, 0.2, 0.3}, {-1e6, 2.5, 1.0 / 3.0}, {7, 8, 9}};
  for (const auto& v : xyz) {
    for (double c : v) put_be(bytes, c);
    put_be(bytes, std::int16_t{-3});
  }
  put_be(bytes, std::int32_t{3});
  for (int i : {2, 0, 1}) put_be(bytes, static_cast<std::uint16_t>(i));
  write_bytes(dir.file("be.ply"), bytes);
  const Mesh mesh = read_mesh(dir.file("be.ply"));
  ASSERT_EQ(mesh.vertices.size(), 3u);
  EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(-1e6, 2.5, 1.0 / 3.0));
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(7, 8, 9));
  ASSERT_EQ(mesh.faces.size(), 1u);
  EXPECT_EQ(mesh.faces[0], (Face{2, 0, 1}));
}

TEST(Ply, TruncatedBinaryNamesTheFileAndTheElement) {
  test::TempDir dir;
  write_mesh(dir.file("m.ply"), test::grid_mesh(3, 3, false));
  const std::string bytes = read_bytes(dir.file("m.ply"));
  write_bytes(dir.file("cut.ply"), bytes.substr(0, bytes.size() - 20));
  const std::string message = error_of([&] { read_mesh(dir.file("cut.ply")); });
  EXPECT_CONTAINS(message, dir.file("cut.ply"));
  EXPECT_CONTAINS(message, "face 16");  // 18 faces of 13 bytes: the 17th is the first incomplete one
  EXPECT_CONTAINS(message, "truncated");
}

TEST(Ply, HeaderClaimingMoreVerticesThanTheFileHoldsIsRejectedBeforeAllocating) {
  test::TempDir dir;
  write_bytes(dir.file("big.ply"),
              "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n" +
                  std::string(24, '\0'));
  const std::string message = error_of([&] { read_cloud(dir.file("big.ply")); });
  EXPECT_CONTAINS(message, dir.file("big.ply") + ": header claims 4000000000 vertices (at least 48000000000 bytes)");
  EXPECT_CONTAINS(message, "only 24 bytes follow");
}

TEST(Ply, AsciiHeaderClaimingMoreFacesThanTheFileHoldsIsRejected) {
  test::TempDir dir;
  write_bytes(dir.file("a.ply"),
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
              "3 0 1 2\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("a.ply")); }), "header claims 1000 faces");
}

TEST(Ply, OutOfRangeFaceIndexIsAnErrorWithTheFaceAndLine) {
  test::TempDir dir;
  write_bytes(dir.file("a.ply"),
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
              "3 0 1 2\n3 0 1 3\n");
  const std::string message = error_of([&] { read_mesh(dir.file("a.ply")); });
  EXPECT_CONTAINS(message, dir.file("a.ply") + ":14: face 1: refers to vertex 3 but the file has 3 vertices");

  Mesh mesh = test::grid_mesh(1, 1, false);
  write_mesh(dir.file("b.ply"), mesh);
  std::string bytes = read_bytes(dir.file("b.ply"));
  bytes[bytes.size() - 4] = 100;  // the last index of the last face
  write_bytes(dir.file("b.ply"), bytes);
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("b.ply")); }), "face 1: refers to vertex 100");
}

TEST(Ply, BadAsciiTokenNamesLineAndVertex) {
  test::TempDir dir;
  write_bytes(dir.file("a.ply"),
              "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
              "end_header\n0 0 0\n1 zero 0\n");
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("a.ply")); }),
                  dir.file("a.ply") + ":9: vertex 1: 'zero' is not a number");
}

TEST(Ply, MalformedHeadersAreErrorsWithTheLine) {
  test::TempDir dir;
  const std::string start = "ply\nformat ascii 1.0\n";
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {"plx\n", "not a PLY file"},
      {start + "element vertex 1\nproperty float x\n", "no 'end_header'"},
      {start + "element vertex 1\nproperty quad x\nend_header\n", ":4: unknown PLY property type 'quad'"},
      {start + "element vertex -1\nend_header\n", ":3: element 'vertex': count '-1'"},
      {start + "element vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", "no x, y and z"},
      {start + "element face 0\nproperty list uchar int vertex_indices\nend_header\n", "no 'vertex' element"},
      {"ply\nformat binary_middle_endian 1.0\nend_header\n", "unknown PLY format"},
  };
  for (const auto& c : cases) {
    write_bytes(dir.file("h.ply"), c.text);
    const std::string message = error_of([&] { read_geometry(dir.file("h.ply")); });
    EXPECT_CONTAINS(message, dir.file("h.ply"));
    EXPECT_CONTAINS(message, c.expected);
  }
}

TEST(Ply, ElementWithoutPropertiesAndAHugeCountIsSkippedAtOnce) {
  test::TempDir dir;
  write_bytes(dir.file("e.ply"),
              "ply\nformat ascii 1.0\nelement nothing 18000000000000000000\nelement vertex 1\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n1 2 3\n");
  EXPECT_EQ(read_geometry(dir.file("e.ply")).vertices.at(0), Eigen::Vector3d(1, 2, 3));
}

}  // namespace
}  // namespace conform
