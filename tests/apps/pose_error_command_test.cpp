// `conform pose-error` end to end: the angle and distance between two transform files, in JSON and text, with
// --units, and exit code 2 with the file named for anything but two readable rigid transforms.

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult pose_error(const std::vector<std::string>& args) {
  std::vector<std::string> all{"pose-error"};
  all.insert(all.end(), args.begin(), args.end());
  return test::run(CONFORM_EXE, all);
}

class PoseErrorCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_bytes(a_, "1 0 0 10\n0 1 0 20\n0 0 1 30\n0 0 0 1\n");
    // 30 degrees about z, and 3, 4, 12 mm further (13 mm).
    std::ostringstream b;
    b.precision(17);
    const double c = std::sqrt(3.0) / 2.0, s = 0.5;
    b << c << " " << -s << " 0 13\n" << s << " " << c << " 0 24\n0 0 1 42\n0 0 0 1\n";
    test::write_bytes(b_, b.str());
  }

  test::TempDir dir_;
  const std::string a_ = dir_.file("T_a.txt");
  const std::string b_ = dir_.file("T_b.txt");
};

TEST_F(PoseErrorCommand, JsonGivesRotationInDegreesAndTranslationInMillimetres) {
  const auto r = pose_error({"--transform", a_, "--transform", b_, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["rotation_deg"].get<double>(), 30.0, 1e-12);
  EXPECT_NEAR(j["translation_mm"].get<double>(), 13.0, 1e-12);
  EXPECT_EQ(j["transform_a"], a_);
  EXPECT_EQ(j["transform_b"], b_);
  const auto back = nlohmann::json::parse(pose_error({"--transform", b_, "--transform", a_, "--json"}).out);
  EXPECT_EQ(back["rotation_deg"], j["rotation_deg"]);
  EXPECT_EQ(back["translation_mm"], j["translation_mm"]);
}

TEST_F(PoseErrorCommand, TextAndUnits) {
  const auto r = pose_error({"--transform", a_, "--transform", a_});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "rotation     0.000000000 deg\ntranslation  0.000000000 mm\n");
  const auto m = pose_error({"--transform", a_, "--transform", b_, "--units", "m", "--json"});
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NEAR(nlohmann::json::parse(m.out)["translation_mm"].get<double>(), 13000.0, 1e-9);
}

TEST_F(PoseErrorCommand, AnythingButTwoRigidTransformsIsExitCodeTwo) {
  const std::string missing = dir_.file("missing.txt"), scaled = dir_.file("scaled.txt"), short_ = dir_.file("s.txt");
  test::write_bytes(scaled, "2 0 0 0\n0 2 0 0\n0 0 2 0\n0 0 0 1\n");
  test::write_bytes(short_, "1 0 0\n0 1 0\n");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--transform", a_}, "two"},
      {{"--transform", a_, "--transform", b_, "--transform", a_}, "two"},
      {{"--transform", a_, "--transform", missing}, missing},
      {{"--transform", scaled, "--transform", a_}, scaled},
      {{"--transform", a_, "--transform", short_}, short_},
      {{"--transform", a_, "--transform", b_, "--units", "parsec"}, "parsec"},
      {{}, "--transform"},
  };
  for (const auto& [args, named] : cases) {
    const auto r = pose_error(args);
    EXPECT_EQ(r.exit_code, 2) << named << "\n" << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
}

}  // namespace
}  // namespace conform
