// The pipe protocol between read_cad and its child (core/src/cad_wire.h): what the child sends decodes to the same
// mesh, and a result that does not add up (as a child corrupted by OpenCASCADE might send) is refused with the reason.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "cad_wire.h"

namespace conform::detail {
namespace {

// Two triangles of a unit square, one solid body, a unit and a warning, as the plugin hands them over.
struct Sample {
  std::vector<double> vertices{0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  std::vector<std::int32_t> triangles{0, 1, 2, 0, 2, 3};
  std::vector<std::int32_t> triangle_faces{0, 0};
  conform_cad_face face{};
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
    face.surface = CONFORM_CAD_PLANE;
    face.sense = 1;
    face.triangles = 2;
    face.area_mm2 = 1.0;
    face.axis[2] = 1.0;
    face.centre_mm[0] = face.centre_mm[1] = face.origin_mm[0] = face.origin_mm[1] = 0.5;
    result.triangle_faces = triangle_faces.data();
    result.faces = &face;
    result.face_count = 1;
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
  ASSERT_EQ(out.triangle_faces, std::vector<std::int32_t>({0, 0}));
  ASSERT_EQ(out.faces.size(), 1u);
  EXPECT_EQ(out.faces[0].surface, CONFORM_CAD_PLANE);
  EXPECT_EQ(out.faces[0].axis[2], 1.0);
  EXPECT_EQ(out.faces[0].centre_mm[1], 0.5);
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

// The faces' section (issue 33): every way it can disagree with itself or with the mesh is refused.
TEST(CadWire, FacesThatDoNotAddUpAreRefused) {
  Sample s;
  s.triangle_faces[1] = 1;  // a face that does not exist
  EXPECT_TRUE(refused(s.payload(), 100, "triangle 1 of face 1 of 1"));
  s.triangle_faces[1] = -1;
  EXPECT_TRUE(refused(s.payload(), 100, "triangle 1 of face -1 of 1"));
  s.triangle_faces[1] = 0;
  s.face.surface = 11;
  EXPECT_TRUE(refused(s.payload(), 100, "unknown surface type 11"));
  s.face.surface = CONFORM_CAD_CYLINDER;
  EXPECT_TRUE(refused(s.payload(), 100, "a radius that is not > 0"));
  s.face.radius_mm = 5.0;
  s.face.axis[2] = 2.0;
  EXPECT_TRUE(refused(s.payload(), 100, "not a unit vector"));
  s.face.axis[2] = 1.0;
  s.face.sense = 0;
  EXPECT_TRUE(refused(s.payload(), 100, "without an outside"));
  s.face.sense = 2;
  EXPECT_TRUE(refused(s.payload(), 100, "orientation out of range"));
  s.face.sense = -1;
  s.face.origin_mm[2] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(refused(s.payload(), 100, "not finite"));
  s.face.origin_mm[2] = 0.0;
  s.face.body = 1;
  EXPECT_TRUE(refused(s.payload(), 100, "body 1 of 1"));
  s.face.body = 0;
  s.face.triangles = 1;
  EXPECT_TRUE(refused(s.payload(), 100, "whose faces do not add up"));
  s.face.triangles = 2;
  s.face.surface = CONFORM_CAD_CONE;
  s.face.half_angle_rad = 1.6;
  EXPECT_TRUE(refused(s.payload(), 100, "cone angle"));
  s.face.half_angle_rad = 0.3;
  s.body.faces = 2;
  EXPECT_TRUE(refused(s.payload(), 100, "do not add up to the bodies' faces"));
  s.body.faces = 1;
  s.result.triangle_faces = nullptr;  // sent without the triangles' faces
  EXPECT_TRUE(refused(s.payload(), 100, "triangle faces for other than every triangle"));
  s.result.triangle_faces = s.triangle_faces.data();
  const std::string good = s.payload();
  CadWireResult out;
  std::string why;
  ASSERT_TRUE(decode_cad_result(good.data(), good.size(), 100, &out, &why)) << why;
  EXPECT_EQ(out.faces[0].sense, -1);
  // Every truncation inside the faces' section (after the warnings) is refused too.
  for (std::size_t n = good.size() - 150; n < good.size(); ++n) {
    EXPECT_FALSE(decode_cad_result(good.data(), n, 100, &out, &why)) << n;
  }
}

// A garbled wire (a child corrupted by OpenCASCADE): random bytes of a valid result overwritten, from a fixed seed.
// Decoding either refuses it or gives a result whose indices are all in range; it never reads out of bounds (the
// sanitizer build runs this too).
TEST(CadWire, GarbledResultsAreRefusedOrConsistent) {
  const Sample s;
  const std::string good = s.payload();
  std::mt19937_64 random(3);
  std::uniform_int_distribution<std::size_t> at(0, good.size() - 1);
  std::uniform_int_distribution<int> byte(0, 255), count(1, 4);
  std::size_t refused_count = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    std::string bad = good;
    for (int k = count(random); k > 0; --k) bad[at(random)] = static_cast<char>(byte(random));
    CadWireResult out;
    std::string why;
    if (!decode_cad_result(bad.data(), bad.size(), 100, &out, &why)) {
      EXPECT_FALSE(why.empty());
      ++refused_count;
      continue;
    }
    ASSERT_EQ(out.triangle_faces.size(), out.mesh.faces.size());
    for (const std::int32_t f : out.triangle_faces) {
      ASSERT_GE(f, 0);
      ASSERT_LT(static_cast<std::size_t>(f), out.faces.size());
    }
    for (const Face& t : out.mesh.faces) {
      for (const std::int32_t v : t) ASSERT_LT(static_cast<std::size_t>(v), out.mesh.vertices.size());
    }
  }
  EXPECT_GT(refused_count, 1000u);  // most corruptions are caught (the rest changed a value that can take any)
}

}  // namespace
}  // namespace conform::detail
