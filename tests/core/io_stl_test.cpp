#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

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

// STL stores corners by value, so the check is per face corner: the coordinates rounded to float (tolerance: none),
// with the corners welded back into the grid's (nx+1)(ny+1) vertices.
void expect_same_triangles(const Mesh& got, const Mesh& want) {
  ASSERT_EQ(got.faces.size(), want.faces.size());
  for (std::size_t f = 0; f < want.faces.size(); ++f) {
    for (std::size_t c = 0; c < 3; ++c) {
      ASSERT_EQ(got.vertices[static_cast<std::size_t>(got.faces[f][c])],
                test::as_float(want.vertices[static_cast<std::size_t>(want.faces[f][c])]))
          << "face " << f << " corner " << c;
    }
  }
  EXPECT_EQ(got.vertices.size(), want.vertices.size());
  EXPECT_FALSE(got.has_normals());
}

class StlRoundTrip : public ::testing::TestWithParam<Encoding> {};

TEST_P(StlRoundTrip, TrianglesComeBackWelded) {
  test::TempDir dir;
  const Mesh mesh = test::grid_mesh(9, 6, true);
  write_mesh(dir.file("m.stl"), mesh, {GetParam(), false});
  ReadReport report;
  expect_same_triangles(read_mesh(dir.file("m.stl"), {}, &report), mesh);
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_EQ(dir.listing(), "m.stl\n");
}

TEST_P(StlRoundTrip, SameMeshGivesSameBytes) {
  test::TempDir dir;
  const Mesh mesh = test::grid_mesh(3, 2, false);
  write_mesh(dir.file("a.stl"), mesh, {GetParam(), false});
  write_mesh(dir.file("b.stl"), mesh, {GetParam(), false});
  EXPECT_EQ(read_bytes(dir.file("a.stl")), read_bytes(dir.file("b.stl")));
}

INSTANTIATE_TEST_SUITE_P(Stl, StlRoundTrip, ::testing::Values(Encoding::kBinary, Encoding::kAscii));

TEST(Stl, BinaryLayoutHasFixedHeaderCountAndUnitNormals) {
  test::TempDir dir;
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  mesh.faces = {{0, 1, 2}};
  write_mesh(dir.file("t.stl"), mesh);
  const std::string bytes = read_bytes(dir.file("t.stl"));
  ASSERT_EQ(bytes.size(), 84u + 50u);
  EXPECT_NE(bytes.substr(0, 5), "solid");  // would make sniffing readers take it for ascii
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  EXPECT_EQ(count, 1u);
  float normal[3];
  std::memcpy(normal, bytes.data() + 84, sizeof(normal));
  EXPECT_EQ(normal[0], 0.0f);
  EXPECT_EQ(normal[1], 0.0f);
  EXPECT_EQ(normal[2], 1.0f);
}

std::string binary_stl(const std::string& header, const std::vector<std::array<float, 9>>& triangles) {
  std::string bytes = header;
  bytes.resize(80, ' ');
  const auto count = static_cast<std::uint32_t>(triangles.size());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : triangles) {
    bytes.append(12, '\0');  // normal
    bytes.append(reinterpret_cast<const char*>(t.data()), 36);
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST(Stl, BinaryWhoseHeaderSaysSolidIsReadAsBinaryAndMinusZeroWelds) {
  test::TempDir dir;
  write_bytes(dir.file("s.stl"),
              binary_stl("solid made by a CAD system", {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {-0.0f, 0, 0, 0, 1, 0, 0, 0, 1}}));
  const Mesh mesh = read_mesh(dir.file("s.stl"));
  EXPECT_EQ(mesh.vertices.size(), 4u);  // (0,0,0) and (-0,0,0) are one vertex
  EXPECT_EQ(mesh.faces[1][0], 0);
  EXPECT_EQ(mesh.faces[1][1], 2);
  EXPECT_EQ(mesh.vertices[3], Eigen::Vector3d(0, 0, 1));
}

TEST(Stl, AsciiWrittenByHand) {
  test::TempDir dir;
  write_bytes(dir.file("a.stl"),
              "solid part one\n"
              "  facet normal 0 0 1\n"
              "    outer loop\n"
              "      vertex 0 0 0\n"
              "      vertex 1.5 0 0\n"
              "      vertex 0 2.5e-1 0\n"
              "    endloop\n"
              "  endfacet\n"
              "  FACET NORMAL 0 0 1\r\n"
              "    OUTER LOOP\r\n"
              "      VERTEX 1.5 0 0\r\n"
              "      VERTEX 1.5 0.25 0\r\n"
              "      VERTEX 0 0.25 0\r\n"
              "    ENDLOOP\r\n"
              "  ENDFACET\r\n"
              "endsolid part one\n"
              "solid second\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 0\nendloop\nendfacet\n"
              "endsolid\n");
  ReadReport report;
  const Mesh mesh = read_mesh(dir.file("a.stl"), {}, &report);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  EXPECT_EQ(mesh.vertices[2], Eigen::Vector3d(0, 0.25, 0));
  ASSERT_EQ(mesh.faces.size(), 2u);
  EXPECT_EQ(mesh.faces[1], (Face{1, 3, 2}));
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_CONTAINS(report.warnings[0], "skipped 1 facets with fewer than 3 vertices");
}

TEST(Stl, AsciiErrorsGiveTheLine) {
  test::TempDir dir;
  const std::string start = "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
  write_bytes(dir.file("a.stl"), start + "vertex 1 oops 0\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("a.stl")); }), dir.file("a.stl") + ":5: 'oops' is not a number");
  write_bytes(dir.file("b.stl"), start + "vertex 1 0 0\nvertex 0 1 0\nendloop\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("b.stl")); }), "unexpected end of file, expected 'endfacet'");
  write_bytes(dir.file("c.stl"), start + "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nfacet\n");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("c.stl")); }), dir.file("c.stl") + ":10: ");
}

TEST(Stl, TruncatedBinaryNamesTheFileAndTheCounts) {
  test::TempDir dir;
  write_mesh(dir.file("m.stl"), test::grid_mesh(2, 2, false));  // 8 triangles
  const std::string bytes = read_bytes(dir.file("m.stl"));
  write_bytes(dir.file("cut.stl"), bytes.substr(0, bytes.size() - 30));
  const std::string message = error_of([&] { read_mesh(dir.file("cut.stl")); });
  EXPECT_CONTAINS(message, dir.file("cut.stl"));
  EXPECT_CONTAINS(message, "header claims 8 triangles (84 + 50 * 8 = 484 bytes) but the file has 454 bytes");
  EXPECT_CONTAINS(message, "does not start with 'solid'");
}

TEST(Stl, HeaderClaimingMoreTrianglesThanTheFileHolds) {
  test::TempDir dir;
  std::string bytes = binary_stl("solid but binary", {{0, 0, 0, 1, 0, 0, 0, 1, 0}});
  const std::uint32_t claimed = 3000000000u;
  std::memcpy(&bytes[80], &claimed, 4);
  write_bytes(dir.file("big.stl"), bytes);
  const std::string message = error_of([&] { read_mesh(dir.file("big.stl")); });
  EXPECT_CONTAINS(message, dir.file("big.stl"));
  EXPECT_CONTAINS(message, "header claims 3000000000 triangles (84 + 50 * 3000000000 = 150000000084 bytes)");
}

TEST(Stl, TooShortAndNotAscii) {
  test::TempDir dir;
  write_bytes(dir.file("x.stl"), "garbage");
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("x.stl")); }), "too short for binary STL (7 bytes");
}

TEST(Stl, CloudsAndFacelessMeshesCannotBeWritten) {
  test::TempDir dir;
  EXPECT_CONTAINS(error_of([&] { write_cloud(dir.file("c.stl"), test::random_cloud(3, false)); }),
                  dir.file("c.stl") + ": STL holds only triangles");
  EXPECT_CONTAINS(error_of([&] { write_mesh(dir.file("m.stl"), to_mesh(test::random_cloud(3, false))); }),
                  "the mesh has no faces");
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
