// write_ply_with_attributes: conform's reader still reads the geometry (and says which properties it ignored), the
// scalars and colours read back by an independent parser, and a mesh without attributes gives write_ply's bytes.

#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "ply_vertex_properties.h"
#include "temp_dir.h"

namespace conform {
namespace {

Mesh square() {
  Mesh m;
  m.vertices = {{0, 0, 0}, {10.5, 0, 0}, {10.5, 10.25, 0}, {0, 10.25, 1e-3}};
  m.faces = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

VertexAttributes deviation_map() {
  VertexAttributes a;
  a.scalars.push_back({"deviation_mm", {-0.125f, 0.0f, 0.3f, 2.5e-5f}});
  a.scalars.push_back({"quality", {1.0f, 2.0f, 3.0f, 4.0f}});
  a.colors = {{{0, 0, 255}}, {{0, 200, 0}}, {{255, 0, 0}}, {{1, 2, 3}}};
  return a;
}

class PlyAttributes : public ::testing::TestWithParam<Encoding> {};

TEST_P(PlyAttributes, GeometryReadsBackAndAttributesParseBack) {
  test::TempDir dir;
  const std::string path = dir.file("deviation.ply");
  WriteOptions options;
  options.encoding = GetParam();
  Mesh mesh = square();
  mesh.normals = vertex_normals_from_faces(mesh);
  write_ply_with_attributes(path, mesh, deviation_map(), options);

  ReadReport report;
  const Mesh back = read_mesh(path, {}, &report);
  ASSERT_EQ(back.vertices.size(), 4u);
  EXPECT_EQ(back.faces, mesh.faces);
  EXPECT_TRUE(back.has_normals());
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(back.vertices[i].cast<float>(), mesh.vertices[i].cast<float>());
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("ignored vertex properties: deviation_mm, quality, red, green, blue"),
            std::string::npos)
      << report.warnings[0];

  const test::PlyVertexProperties p = test::read_ply_vertex_properties(test::read_bytes(path));
  ASSERT_EQ(p.error, "");
  EXPECT_EQ(p.names, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "deviation_mm", "quality", "red",
                                               "green", "blue"}));
  const VertexAttributes expected = deviation_map();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(p.values.at("deviation_mm")[i], static_cast<double>(expected.scalars[0].second[i])) << i;
    EXPECT_EQ(p.values.at("quality")[i], static_cast<double>(expected.scalars[1].second[i])) << i;
    EXPECT_EQ(p.values.at("red")[i], expected.colors[i][0]);
    EXPECT_EQ(p.values.at("green")[i], expected.colors[i][1]);
    EXPECT_EQ(p.values.at("blue")[i], expected.colors[i][2]);
  }
}

TEST_P(PlyAttributes, WithoutAttributesTheBytesAreWritePlys) {
  test::TempDir dir;
  WriteOptions options;
  options.encoding = GetParam();
  write_mesh(dir.file("plain.ply"), square(), options);
  write_ply_with_attributes(dir.file("attributes.ply"), square(), {}, options);
  EXPECT_EQ(test::read_bytes(dir.file("plain.ply")), test::read_bytes(dir.file("attributes.ply")));
}

TEST_P(PlyAttributes, ACloudAndNonFiniteValuesAreWritten) {
  test::TempDir dir;
  const std::string path = dir.file("cloud.ply");
  WriteOptions options;
  options.encoding = GetParam();
  Mesh cloud = square();
  cloud.faces.clear();
  VertexAttributes a;
  a.scalars.push_back({"deviation_mm", {1.0f, std::numeric_limits<float>::quiet_NaN(), -1.0f, 0.5f}});
  write_ply_with_attributes(path, cloud, a, options);
  EXPECT_EQ(read_geometry(path).vertices.size(), 4u);
  const test::PlyVertexProperties p = test::read_ply_vertex_properties(test::read_bytes(path));
  ASSERT_EQ(p.error, "");
  EXPECT_TRUE(std::isnan(p.values.at("deviation_mm")[1]));
  EXPECT_EQ(p.values.at("deviation_mm")[3], 0.5);
}

INSTANTIATE_TEST_SUITE_P(Encodings, PlyAttributes, ::testing::Values(Encoding::kBinary, Encoding::kAscii));

TEST(PlyAttributesErrors, NameThePathAndLeaveNothingBehind) {
  test::TempDir dir;
  const Mesh mesh = square();
  VertexAttributes short_scalar;
  short_scalar.scalars.push_back({"deviation_mm", {1.0f, 2.0f}});
  VertexAttributes bad_name;
  bad_name.scalars.push_back({"deviation mm", {1, 2, 3, 4}});
  VertexAttributes taken;
  taken.scalars.push_back({"red", {1, 2, 3, 4}});
  VertexAttributes short_colours;
  short_colours.colors = {{{1, 2, 3}}};
  const std::string path = dir.file("out.ply");
  for (const VertexAttributes* a : {&short_scalar, &bad_name, &taken, &short_colours}) {
    try {
      write_ply_with_attributes(path, mesh, *a);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(write_ply_with_attributes(dir.file("out.stl"), mesh, {}), Error);
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
