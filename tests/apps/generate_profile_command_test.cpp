// `conform generate profile` end to end: the files it writes, its JSON, the same bytes on a rerun, exit 2 on bad input.

#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

test::RunResult generate(std::vector<std::string> args) {
  args.insert(args.begin(), {"generate", "profile"});
  return test::run(CONFORM_EXE, args);
}

TEST(GenerateProfileCommand, WritesTheEdgeFeaturesAndTruth) {
  test::TempDir dir;
  const auto r = generate({"--out", dir.file("p.csv"), "--length", "3000", "--holes", "3", "--second-edge",
                           "--kink-deg", "0.5", "--kink-at", "1000", "--dropouts", "0.05", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["features"], 3);
  EXPECT_EQ(j["length_mm"], 3000.0);
  EXPECT_NEAR(j["kink_deg"].get<double>(), 0.5, 1e-12);
  EXPECT_EQ(j["edge_points"].get<int>() + j["dropped"].get<int>(), 601);
  EXPECT_EQ(dir.listing(), "p.csv\np.edge2.csv\np.features.csv\np.truth.csv\np.truth.json\n");
  const std::string features = test::read_bytes(dir.file("p.features.csv"));
  EXPECT_EQ(features.substr(0, features.find('\n')), "id,type,tx_mm,ty_mm,radius_mm");
  EXPECT_NE(features.find("H2,circle,100.000000,1500.000000,50.000000"), std::string::npos) << features;
  // Text output by default, and the same bytes on a rerun.
  const auto again = generate({"--out", dir.file("q.csv"), "--length", "3000", "--holes", "3", "--second-edge",
                               "--kink-deg", "0.5", "--kink-at", "1000", "--dropouts", "0.05"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("edge       "), std::string::npos);
  EXPECT_EQ(test::read_bytes(dir.file("q.csv")), test::read_bytes(dir.file("p.csv")));
  EXPECT_EQ(test::read_bytes(dir.file("q.truth.csv")), test::read_bytes(dir.file("p.truth.csv")));
}

TEST(GenerateProfileCommand, BadOptionsExitTwoAndWriteNothing) {
  test::TempDir dir;
  auto r = generate({"--out", dir.file("p.csv"), "--spacing", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("spacing_mm"), std::string::npos) << r.err;
  r = generate({"--out", dir.file("p.ply")});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".csv"), std::string::npos) << r.err;
  r = generate({"--out", dir.file("p.csv"), "--bow-asymmetry", "2"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
