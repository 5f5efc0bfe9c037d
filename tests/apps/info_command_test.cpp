// `conform info` on good files and on every kind of malformed file the foundation issue lists:
// each bad file gives exit code 2 and a message naming the file and the problem, and nothing crashes.

#include <cstdint>
#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult info(const std::vector<std::string>& args) {
  std::vector<std::string> all{"info"};
  all.insert(all.end(), args.begin(), args.end());
  return test::run(CONFORM_EXE, all);
}

template <typename T>
void append(std::string& bytes, T value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.append(raw, sizeof(T));
}

// A binary STL holding `triangles` triangles of which only `written` are present.
std::string binary_stl(std::uint32_t triangles, std::uint32_t written) {
  std::string bytes(80, ' ');
  append(bytes, triangles);
  for (std::uint32_t t = 0; t < written; ++t) {
    const float f[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, static_cast<float>(t)};
    for (float v : f) append(bytes, v);
    append(bytes, std::uint16_t{0});
  }
  return bytes;
}

// A binary PLY whose header claims `claimed` vertices but whose body holds `written`.
std::string binary_ply(int claimed, int written) {
  std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(claimed) +
                      "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (int i = 0; i < written; ++i) {
    for (float v : {1.0f * static_cast<float>(i), 2.0f, 3.0f}) append(bytes, v);
  }
  return bytes;
}

struct BadFile {
  const char* name;
  std::string bytes;
  const char* problem;  // a word the message must contain (lower-case)
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

TEST(InfoCommand, DescribesAGoodCloudInTextAndJson) {
  test::TempDir dir;
  const std::string path = dir.file("points.xyz");
  test::write_bytes(path, "x y z\n0 0 0\n10 0 0\n0 20 0\n0 0 30.5\n");

  const auto text = info({path});
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("points       4"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("box size mm  10.0000 20.0000 30.5000"), std::string::npos) << text.out;

  const auto json = info({path, "--json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);  // stdout holds one JSON object and nothing else
  EXPECT_EQ(j["points"], 4);
  EXPECT_EQ(j["faces"], 0);
  EXPECT_EQ(j["non_finite_points"], 0);
  EXPECT_EQ(j["has_normals"], false);
  EXPECT_EQ(j["bounding_box_size_mm"], nlohmann::json({10.0, 20.0, 30.5}));
}

TEST(InfoCommand, DescribesAMeshWithFacesAndArea) {
  test::TempDir dir;
  const std::string path = dir.file("square.obj");
  test::write_bytes(path, "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nf 1 2 3 4\n");
  const auto r = info({path, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], 4);
  EXPECT_EQ(j["faces"], 2);  // the quad, fan-triangulated
  EXPECT_DOUBLE_EQ(j["surface_area_mm2"].get<double>(), 100.0);
}

// --units m: a range sensor's file in metres, shown in millimetres.
TEST(InfoCommand, UnitsScaleTheBoxAndArea) {
  test::TempDir dir;
  const std::string path = dir.file("square.obj");
  test::write_bytes(path, "v 0 0 0\nv 0.01 0 0\nv 0.01 0.02 0\nv 0 0.02 0\nf 1 2 3 4\n");
  const auto r = info({path, "--units", "m", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["units"], "m");
  EXPECT_NEAR(j["bounding_box_size_mm"][1].get<double>(), 20.0, 1e-12);
  EXPECT_NEAR(j["surface_area_mm2"].get<double>(), 200.0, 1e-9);
  const auto text = info({path, "--units", "m"});
  EXPECT_NE(text.out.find("units        m"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("box size mm  10.0000 20.0000 0.0000"), std::string::npos) << text.out;
  const auto bad = info({path, "--units", "furlong"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("furlong"), std::string::npos) << bad.err;
}

TEST(InfoCommand, CountsNonFinitePointsAndStillRefusesTheFile) {
  test::TempDir dir;
  const std::string path = dir.file("with_nan.csv");
  test::write_bytes(path, "x,y,z\n1,2,3\nnan,0,0\n4,5,inf\n7,8,9\n");
  const auto r = info({path, "--json"});
  EXPECT_EQ(r.exit_code, 2);
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["points"], 4);
  EXPECT_EQ(j["non_finite_points"], 2);
  EXPECT_EQ(j["bounding_box_size_mm"], nlohmann::json({6.0, 6.0, 6.0}));
  EXPECT_NE(r.err.find(path), std::string::npos) << r.err;
  EXPECT_NE(lower(r.err).find("nan"), std::string::npos) << r.err;
}

TEST(InfoCommand, MalformedFilesGiveExitCodeTwoAndAMessageNamingFileAndProblem) {
  const std::vector<BadFile> bad = {
      {"truncated.stl", binary_stl(10, 9) + std::string(30, '\0'), "truncated"},
      {"claims_more.stl", binary_stl(1000000, 2), "1000000"},
      {"truncated.ply", binary_ply(5, 4) + std::string(6, '\0'), "truncated"},
      {"claims_more.ply", binary_ply(2000000000, 3), "2000000000"},
      {"letters.xyz", "1 2 3\n4 five 6\n", "five"},
      {"letters.csv", "x,y,z\n1,2,3\n4,5,6\n7,8,z9\n", "z9"},
      {"nan.ply",
       "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
       "end_header\n0 0 0\nnan 1 1\n",
       "nan"},
      {"inf.xyz", "1 2 3\ninf 0 0\n", "inf"},
      {"empty.ply", "", "empty"},
      {"empty.stl", "", "empty"},
      {"empty.xyz", "", "empty"},
      {"header_only.xyz", "x y z\n", "no points"},
      {"unknown.abc", "1 2 3\n", ".abc"},
      {"face_out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "9"},
      {"not_a_ply.ply", "hello\n", "ply"},
  };
  test::TempDir dir;
  for (const BadFile& b : bad) {
    const std::string path = dir.file(b.name);
    test::write_bytes(path, b.bytes);
    const auto r = info({path});
    EXPECT_EQ(r.signal, 0) << b.name << " crashed conform";
    EXPECT_EQ(r.exit_code, 2) << b.name << ": " << r.err;
    EXPECT_NE(r.err.find(path), std::string::npos) << b.name << ": the message does not name the file: " << r.err;
    EXPECT_NE(lower(r.err).find(b.problem), std::string::npos)
        << b.name << ": the message does not say '" << b.problem << "': " << r.err;
  }
}

TEST(InfoCommand, MissingFileIsBadInput) {
  const auto r = info({"/nonexistent/scan.ply"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/scan.ply"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace conform
