// Regression tests for the PCD files of issue 18 (found by fuzzing): conform's own parser reads every SIZE/TYPE,
// checks each ascii value against its field's type, and matches the body's size exactly against the header.

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
using test::write_bytes;

std::string header(const std::string& points, const std::string& data, const std::string& fields = "x y z",
                   const std::string& sizes = "4 4 4", const std::string& types = "F F F") {
  return "# .PCD v0.7\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes + "\nTYPE " + types +
         "\nCOUNT 1 1 1\nWIDTH " + points + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\nDATA " + data +
         "\n";
}

template <typename T>
void append(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));  // little-endian hosts only, like the PCD files in circulation
  bytes.append(raw, sizeof(T));
}

std::string floats(std::initializer_list<float> values) {
  std::string bytes;
  for (float v : values) append(bytes, v);
  return bytes;
}

// Was a heap-buffer-overflow: the header check stopped at DATA while PCL read "SIZE 8 8 8" after it as a keyword.
TEST(PcdHostile, BinaryBodyThatLooksLikeAHeaderLineIsData) {
  test::TempDir dir;
  const std::string path = dir.file("s.pcd");
  write_bytes(path, header("2", "binary") + "SIZE 8 8 8\n" + floats({1, 2, 3, 4, 5, 6}));
  EXPECT_CONTAINS(error_of([&] { read_cloud(path); }), "claims 2 points (24 bytes) but 35 bytes follow the DATA line");
  // Sized to fit, the text is read as the 24 bytes of data it is, the same on every run.
  write_bytes(path, header("2", "binary") + "SIZE 8 8 8\n" + std::string(13, '\0'));
  const Mesh mesh = read_geometry(path, {NonFinitePolicy::kKeep});
  ASSERT_EQ(mesh.vertices.size(), 2u);
  EXPECT_EQ(mesh.vertices[1], Eigen::Vector3d(0, 0, 0));
}

// Was a SIGSEGV inside PCL.
TEST(PcdHostile, WhitespaceOnlyHeaderLineIsBlank) {
  test::TempDir dir;
  write_bytes(dir.file("w.pcd"), "FIELDS x y z\n \t \r\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
  const Cloud cloud = read_cloud(dir.file("w.pcd"));
  ASSERT_EQ(cloud.size(), 1u);
  EXPECT_EQ(cloud.points[0].getVector3fMap(), Eigen::Vector3f(1, 2, 3));
}

// Were read as zeros. 2^40 + 1 is exact in a double; tolerance none.
TEST(PcdHostile, EightByteIntegersAreRead) {
  test::TempDir dir;
  std::string body;
  append(body, std::int64_t{-5});
  append(body, std::uint64_t{(std::uint64_t{1} << 40) + 1});
  append(body, 1.5);
  write_bytes(dir.file("b.pcd"), header("1", "binary", "x y z", "8 8 8", "I U F") + body);
  write_bytes(dir.file("a.pcd"), header("1", "ascii", "x y z", "8 8 8", "I U F") + "-5 1099511627777 1.5\n");
  for (const char* name : {"b.pcd", "a.pcd"}) {
    const Mesh mesh = read_geometry(dir.file(name));
    ASSERT_EQ(mesh.vertices.size(), 1u);
    EXPECT_EQ(mesh.vertices[0], Eigen::Vector3d(-5, 1099511627777.0, 1.5)) << name;
  }
}

// Were wrapped or truncated (255, INT_MIN, 2) with exit 0.
TEST(PcdHostile, AsciiValuesOutsideTheirTypeAreErrorsNamingLineAndField) {
  test::TempDir dir;
  const struct {
    std::string sizes, types, line, expected;
  } cases[] = {
      {"4 4 1", "F F U", "1 2 -1", ":12: field 'z' (TYPE U SIZE 1): '-1' is out of range (0 to 255)"},
      {"4 4 4", "F F I", "1 2 3e11", ":12: field 'z' (TYPE I SIZE 4): '3e11' is out of range (-2147483648 to"},
      {"4 4 4", "F F I", "1 2 300000000000", "'300000000000' is out of range (-2147483648 to 2147483647)"},
      {"4 2 4", "F I F", "1 2.9 3", ":12: field 'y' (TYPE I SIZE 2): '2.9' is not an integer (-32768 to 32767)"},
      {"4 4 4", "F F F", "1 2 1e39", ":12: field 'z' (TYPE F SIZE 4): '1e39' is out of range for a 4-byte float"},
      {"8 4 4", "F F F", "1e400 2 3", ":12: field 'x' (TYPE F SIZE 8): '1e400' is out of range"},
      {"4 4 4", "F F F", "1 2 3 4", ":12: expected 3 values, found 4"},
  };
  for (const auto& c : cases) {
    write_bytes(dir.file("v.pcd"), header("1", "ascii", "x y z", c.sizes, c.types) + c.line + "\n");
    const std::string message = error_of([&] { read_cloud(dir.file("v.pcd")); });
    EXPECT_CONTAINS(message, dir.file("v.pcd"));
    EXPECT_CONTAINS(message, c.expected);
  }
}

// A decompression bomb: the header asks for 1.2 GB from 100 bytes. Refused before allocating.
TEST(PcdHostile, CompressedSizeIsCappedByTheFileSize) {
  test::TempDir dir;
  std::string body;
  append(body, std::uint32_t{100});
  append(body, std::uint32_t{1'200'000'000});
  body += std::string(100, '\0');
  write_bytes(dir.file("z.pcd"), header("100000000", "binary_compressed") + body);
  EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("z.pcd")); }),
                  "100 compressed bytes cannot hold the 1200000000 bytes the header claims (LZF expands at most 88");
}

// Our own LZF decoder on a hand-made stream: a literal zero, then a 23-byte back-reference 1 byte back (overlapping).
TEST(PcdHostile, LzfBackReferenceOverlapsItsOutput) {
  test::TempDir dir;
  std::string body;
  append(body, std::uint32_t{5});
  append(body, std::uint32_t{24});
  body += std::string("\x00\x00\xe0\x0e\x00", 5);
  write_bytes(dir.file("z.pcd"), header("2", "binary_compressed") + body);
  const Cloud cloud = read_cloud(dir.file("z.pcd"));
  ASSERT_EQ(cloud.size(), 2u);
  EXPECT_EQ(cloud.points[1].getVector3fMap(), Eigen::Vector3f(0, 0, 0));
  // A reference before the output's start, a stream one byte short and one with a byte to spare are all damage.
  for (const std::string& stream : {std::string("\xe0\x0e\x00", 3), std::string("\x00\x00\xe0\x0d\x00", 5),
                                    std::string("\x00\x00\xe0\x0e\x00\x00", 6)}) {
    std::string damaged;
    append(damaged, static_cast<std::uint32_t>(stream.size()));
    append(damaged, std::uint32_t{24});
    write_bytes(dir.file("d.pcd"), header("2", "binary_compressed") + damaged + stream);
    EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("d.pcd")); }), "the compressed PCD data is damaged");
  }
}

TEST(PcdHostile, HeaderKeywordsOnceAndFieldsNamedOnce) {
  test::TempDir dir;
  const struct {
    std::string bytes, expected;
  } cases[] = {
      {"FIELDS x y z\nSIZE 4 4\n", ":2: SIZE has 2 entries for 3 FIELDS"},
      {"FIELDS x y x\nSIZE 4 4 4\nTYPE F F F\nDATA ascii\n", ":4: field 'x' named twice"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1\nWIDTH 1\n", ":5: WIDTH given twice"},
      {"FIELDS x y z\nSIZE 4 4 16\nTYPE F F F\nDATA ascii\n", "field 'z' has an unsupported SIZE/TYPE (16 F"},
      {"FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\nDATA ascii\n", "field 'z' has an unsupported SIZE/TYPE (2 F"},
      {"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 0\nDATA ascii\n", "field 'z' has a COUNT out of range"},
  };
  for (const auto& c : cases) {
    write_bytes(dir.file("h.pcd"), c.bytes);
    EXPECT_CONTAINS(error_of([&] { read_cloud(dir.file("h.pcd")); }), c.expected);
  }
}

}  // namespace
}  // namespace conform
