// Hostile inputs at the command line (issue 18): non-UTF-8 file names in --json output and messages, FIFOs and
// devices as inputs, numbers out of JSON's range. Each is exit 2 with a message naming the file, or (a strange but
// valid name) exit 0 with valid JSON.

#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

// Was nlohmann type_error 316, exit 1, after the work was done.
TEST(BadInputCommand, NonUtf8FileNameGivesValidJsonAndAnEscapedMessage) {
  test::TempDir dir;
  const std::string name = dir.file(std::string("a\xff\x1b.xyz"));
  test::write_bytes(name, "1 2 3\n4 5 6\n7 8 10\n");
  const test::RunResult ok = test::run(CONFORM_EXE, {"info", name, "--json"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const nlohmann::json j = nlohmann::json::parse(ok.out);
  EXPECT_EQ(j["points"], 3);
  EXPECT_NE(j["file"].get<std::string>().find("a\xef\xbf\xbd\x1b.xyz"), std::string::npos);  // U+FFFD for 0xff

  const test::RunResult missing = test::run(CONFORM_EXE, {"info", dir.file(std::string("b\xff\x1b.xyz"))});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("b\\xff\\x1b.xyz: cannot open"), std::string::npos) << missing.err;
}

TEST(BadInputCommand, FifoAndDeviceInputsAreRefused) {
  test::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("f.ply").c_str(), 0600), 0);
  const test::RunResult fifo = test::run(CONFORM_EXE, {"info", dir.file("f.ply")});
  EXPECT_EQ(fifo.exit_code, 2);
  EXPECT_NE(fifo.err.find("f.ply: is a FIFO (named pipe), not a regular file"), std::string::npos) << fifo.err;
}

// Was nlohmann out_of_range, "internal error", exit 1.
TEST(BadInputCommand, FeaturesJsonNumberOutOfRangeIsBadInput) {
  test::TempDir dir;
  std::string edge = "x_mm,y_mm,z_mm\n";
  for (int i = 0; i <= 40; ++i) edge += std::to_string(i * 25) + ",0,0\n";
  test::write_bytes(dir.file("edge.csv"), edge);
  test::write_bytes(dir.file("f.json"), R"({"features": [{"id": "H1", "type": "hole", "tx_mm": 1e400, "ty_mm": 5}]})");
  const test::RunResult r =
      test::run(CONFORM_EXE, {"profile", "--edge", dir.file("edge.csv"), "--features", dir.file("f.json")});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("f.json: not valid JSON"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace conform
