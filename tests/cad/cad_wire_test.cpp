// The pipe protocol between read_cad and its child (core/src/cad_wire.h): what the child sends decodes to the same
// mesh, and a result that does not add up (as a child corrupted by OpenCASCADE might send) is refused with the reason.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "cad_wire.h"

namespace conform::detail {
namespace {

// Two triangles of a unit square, one solid body, a unit and a warning, as the plugin hands them over.
struct Sample {
  std::vector<double> vertices{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<std::int32_t> triangles{0, 1, 2, 0, 2, 3};
  conform_cad_body body{};
  conform_cad_result result{};
  char warnings[32] = "body 1 is an open shell\n";
  Sample() {
    body.kind = CONFORM_CAD_OPEN_SHELL;
    body.faces = 1;
    body.triangles = 2;
    body.box_max_mm[0] = body.box_max_mm[1] = 1.0;
    std::strncpy(result.file_unit, "INCH", sizeof result.file_unit);
    result.mm_per_file_unit = 25.4;
    result.vertices = vertices.data();
    result.vertex_count = 4;
    result.triangles = triangles.data();
    result.triangle_count = 2;
    result.bodies = &body;
    result.body_count = 1;
    result.warnings = warnings;
  }
  // The 'R' message's payload (without its header).
  std::string payload() const { return cad_result_message(result).substr(kCadWireHeader); }
};

TEST(CadWire, AResultDecodesToTheSameMesh) {
  const Sample s;
  const std::string message = cad_result_message(s.result);
  ASSERT_EQ(message[0], 'R');
  std::uint64_t size = 0;
  std::memcpy(&size, &message[1], sizeof size);
  EXPECT_EQ(size, message.size() - kCadWireHeader);
  CadWireResult out;
  std::string why;
  ASSERT_TRUE(decode_cad_result(message.data() + kCadWireHeader, size, 100, &out, &why)) << why;
  EXPECT_EQ(out.file_unit, "INCH");
  EXPECT_EQ(out.mm_per_file_unit, 25.4);
  ASSERT_EQ(out.mesh.vertices.size(), 4u);
  EXPECT_EQ(out.mesh.vertices[2], Eigen::Vector3d(1, 1, 0));
  ASSERT_EQ(out.mesh.faces.size(), 2u);
  EXPECT_EQ(out.mesh.faces[1][2], 3);
  ASSERT_EQ(out.bodies.size(), 1u);
  EXPECT_EQ(out.bodies[0].kind, CONFORM_CAD_OPEN_SHELL);
  EXPECT_EQ(out.bodies[0].box_max_mm[1], 1.0);
  EXPECT_EQ(out.warnings, "body 1 is an open shell\n");
}

bool refused(const std::string& payload, std::size_t max_triangles, const std::string& reason) {
  CadWireResult out;
  std::string why;
  const bool ok = decode_cad_result(payload.data(), payload.size(), max_triangles, &out, &why);
  EXPECT_NE(why.find(reason), std::string::npos) << why;
  return !ok;
}

TEST(CadWire, AResultThatDoesNotAddUpIsRefused) {
  Sample s;
  const std::string good = s.payload();
  // Every truncation, from the first byte to the last.
  for (std::size_t n = 0; n < good.size(); ++n) {
    CadWireResult out;
    std::string why;
    EXPECT_FALSE(decode_cad_result(good.data(), n, 100, &out, &why)) << n;
  }
  EXPECT_TRUE(refused(good + "x", 100, "1 bytes after the end"));
  EXPECT_TRUE(refused(good, 1, "2 triangles, over the budget of 1"));
  s.triangles[4] = 4;  // one past the last vertex
  EXPECT_TRUE(refused(s.payload(), 100, "triangle 1 has vertex index 4 of 4"));
  s.triangles[4] = 2;
  s.vertices[7] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(refused(s.payload(), 100, "vertex 2 is not finite"));
  s.vertices[7] = 1.0;
  s.body.triangles = 1;
  EXPECT_TRUE(refused(s.payload(), 100, "do not add up"));
  s.body.triangles = 2;
  s.body.kind = 7;
  EXPECT_TRUE(refused(s.payload(), 100, "unknown kind 7"));
  s.body.kind = CONFORM_CAD_SOLID;
  std::string huge = good;
  const std::uint64_t count = std::uint64_t{1} << 60;
  std::memcpy(&huge[4 + 4 + 8], &count, sizeof count);  // after the unit ("INCH", length-prefixed) and the factor
  EXPECT_TRUE(refused(huge, 100, "more vertices than bytes"));
}

}  // namespace
}  // namespace conform::detail
