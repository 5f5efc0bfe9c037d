// Regression tests for the PLY files of issue 18: ascii PLY is read line by line with exact counts, integers are
// checked against their property's type, and polygon sizes are capped.

#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "io_test_data.h"
#include "temp_dir.h"

namespace conform {
namespace {

using test::error_of;
using test::write_bytes;

const std::string kHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

// An extra value used to shift every later value into the next vertex, with exit 0.
TEST(PlyHostile, AsciiValuesKeepToTheirLines) {
  test::TempDir dir;
  const struct {
    std::string body, expected;
  } cases[] = {
      {"0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n", ":10: vertex 0: more values on the line than the element's 3 ('7'"},
      {"0 0\n1 0 0\n0 1 0\n3 0 1 2\n", ":10: vertex 0: the line ends after 2 values"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n0 0 0\n", ":14: more lines than the header's element counts"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 1 2 2\n", ":13: face 0: more values on the line than the element's 4"},
      {"0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n", ":13: face 0: '300' is out of range (0 to 255)"},
      {"0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", ":13: face 0: '1.5' is not an integer"},
      {"0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n", ":13: face 0: a list of 200 values does not fit on its line"},
  };
  for (const auto& c : cases) {
    write_bytes(dir.file("a.ply"), kHeader + c.body);
    const std::string message = error_of([&] { read_mesh(dir.file("a.ply")); });
    EXPECT_CONTAINS(message, dir.file("a.ply"));
    EXPECT_CONTAINS(message, c.expected);
  }
  // Blank lines, CRLF line ends and trailing blank lines are fine.
  write_bytes(dir.file("ok.ply"), kHeader + "0 0 0\r\n\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n\r\n\n");
  const Mesh mesh = read_mesh(dir.file("ok.ply"));
  ASSERT_EQ(mesh.faces.size(), 1u);
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(1, 0, 0));
}

// A 40M-vertex polygon in a 40 MB file took 1.09 GB. Tested at 2000 vertices (the cap is 1000).
TEST(PlyHostile, PolygonSizeIsCapped) {
  test::TempDir dir;
  std::string body;
  for (int i = 0; i < 3; ++i) body.append(12, '\0');
  body += static_cast<char>(0xd0);  // 2000 as a little-endian uint16 count
  body += static_cast<char>(0x07);
  body.append(2000, '\0');
  write_bytes(dir.file("b.ply"),
              "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list ushort uchar vertex_indices\nend_header\n" + body);
  EXPECT_CONTAINS(error_of([&] { read_mesh(dir.file("b.ply")); }),
                  "face 0: a polygon of 2000 vertices (conform reads polygons of up to 1000)");
}

}  // namespace
}  // namespace conform
