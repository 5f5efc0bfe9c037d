// `conform profile` end to end on generated profiles: the compensated CSV against the ground truth, the JSON keys,
// exit code 2 with a message naming the file for bad input, no partial output, the same bytes on a rerun.

#include <algorithm>
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

test::RunResult conform_run(const std::vector<std::string>& args) { return test::run(CONFORM_EXE, args); }

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> fields(const std::string& row) {
  std::vector<std::string> out;
  std::istringstream in(row);
  for (std::string field; std::getline(in, field, ',');) out.push_back(field);
  return out;
}

// A 3 m profile with 3 holes, bow 10 mm; `more` adds generator flags.
std::string make_profile(const test::TempDir& dir, const std::string& name, std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"generate",   "profile", "--out",           dir.file(name), "--length", "3000",
                                   "--bow",      "10",      "--bow-asymmetry", "0.5",          "--holes",  "3",
                                   "--dropouts", "0.02"};
  args.insert(args.end(), more.begin(), more.end());
  const auto r = conform_run(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir.file(name);
}

// The worst distance of an output centre row (i = -1) from the truth row of the same id.
double worst_centre_error(const std::string& out_csv, const std::string& truth_csv) {
  double worst = 0.0;
  const std::vector<std::string> out = lines(out_csv), truth = lines(truth_csv);
  for (std::size_t a = 1; a < out.size(); ++a) {
    const std::vector<std::string> o = fields(out[a]);
    if (o[1] != "-1") continue;
    for (std::size_t b = 1; b < truth.size(); ++b) {
      const std::vector<std::string> t = fields(truth[b]);
      if (t[0] != o[0] || t[1] != "-1") continue;
      const double dx = std::stod(o[4]) - std::stod(t[4]), dy = std::stod(o[5]) - std::stod(t[5]),
                   dz = std::stod(o[6]) - std::stod(t[6]);
      worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  return worst;
}

TEST(ProfileCommand, CompensatesAGeneratedProfile) {
  test::TempDir dir;
  const std::string edge = make_profile(dir, "p.csv");
  const auto r = conform_run(
      {"profile", "--edge", edge, "--features", dir.file("p.features.csv"), "--out", dir.file("out.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // one JSON object and nothing else on stdout
  for (const char* key : {"edge_rms_mm", "edge_max_mm", "model", "features", "arc_length_residual_max_mm"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["model"], "cubic");
  EXPECT_NEAR(j["edge_rms_mm"].get<double>(), 0.14, 0.03);  // sqrt(2) x 0.1 mm of noise
  EXPECT_LE(j["arc_length_residual_max_mm"].get<double>(), 1e-6);
  ASSERT_EQ(j["features"].size(), 3u);
  EXPECT_EQ(j["features"][0]["id"], "H1");
  const std::string out = test::read_bytes(dir.file("out.csv"));
  EXPECT_EQ(lines(out)[0], "id,i,tx_mm,ty_mm,x_mm,y_mm,z_mm,nx,ny,nz,dx,dy,dz");
  // 0.3 mm: the bound for the compensated hole centres.
  EXPECT_LT(worst_centre_error(out, test::read_bytes(dir.file("p.truth.csv"))), 0.3);
  // Circle outlines are closed: the last row of H1 repeats its first (i = 0).
  std::vector<std::string> h1;
  for (const std::string& line : lines(out)) {
    if (line.rfind("H1,", 0) == 0 && line.rfind("H1,-1,", 0) != 0) h1.push_back(line.substr(line.find(',', 3)));
  }
  ASSERT_GT(h1.size(), 20u);
  EXPECT_EQ(h1.front(), h1.back());
  // Same bytes on a rerun, text output without --json.
  const auto again = conform_run(
      {"profile", "--edge", edge, "--features", dir.file("p.features.csv"), "--out", dir.file("again.csv")});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("model         cubic"), std::string::npos) << again.out;
  EXPECT_EQ(test::read_bytes(dir.file("again.csv")), out);
}

TEST(ProfileCommand, SplineAndSecondEdgeOptions) {
  test::TempDir dir;
  const std::string edge =
      make_profile(dir, "k.csv", {"--kink-deg", "1", "--kink-at", "1000", "--second-edge", "--twist-deg", "1"});
  const auto r = conform_run({"profile", "--edge", edge, "--features", dir.file("k.features.csv"), "--second-edge",
                              dir.file("k.edge2.csv"), "--out", dir.file("out.csv"), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["model"], "spline");  // auto, by residual
  EXPECT_EQ(j["web"], "second edge");
  EXPECT_GT(j["cubic_deviation_max_mm"].get<double>(), 0.5);
  EXPECT_GT(j["features"][0]["cubic_deviation_max_mm"].get<double>(), 0.0);
  EXPECT_LT(worst_centre_error(test::read_bytes(dir.file("out.csv")), test::read_bytes(dir.file("k.truth.csv"))), 0.3);
  // --model cubic is obeyed; --web-normal and --second-edge exclude each other.
  const auto cubic = conform_run({"profile", "--edge", edge, "--features", dir.file("k.features.csv"), "--model",
                                  "cubic", "--web-normal", "0.001,0,1", "--json"});
  ASSERT_EQ(cubic.exit_code, 0) << cubic.err;
  EXPECT_EQ(nlohmann::json::parse(cubic.out)["model"], "cubic");
  EXPECT_EQ(nlohmann::json::parse(cubic.out)["web"], "given");
  const auto both = conform_run({"profile", "--edge", edge, "--features", dir.file("k.features.csv"), "--web-normal",
                                 "0,0,1", "--second-edge", dir.file("k.edge2.csv")});
  EXPECT_EQ(both.exit_code, 2);
}

TEST(ProfileCommand, BadInputExitsTwoNamingTheProblem) {
  test::TempDir dir;
  const std::string edge = make_profile(dir, "p.csv");
  const std::string features = dir.file("p.features.csv");
  std::vector<std::string> rows = lines(test::read_bytes(edge));
  const auto write_edge = [&dir](const std::string& name, const std::vector<std::string>& r) {
    std::string text;
    for (const std::string& line : r) text += line + "\n";
    test::write_bytes(dir.file(name), text);
    return dir.file(name);
  };
  const auto expect_error = [&](const std::vector<std::string>& args, const std::vector<std::string>& needles) {
    std::vector<std::string> all = {"profile"};
    all.insert(all.end(), args.begin(), args.end());
    all.insert(all.end(), {"--out", dir.file("never.csv")});
    const auto r = conform_run(all);
    EXPECT_EQ(r.exit_code, 2) << needles.front();
    for (const std::string& needle : needles) EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_TRUE(test::read_bytes(dir.file("never.csv")).empty());
  };
  // Not in measuring order: rows 100 and 101 (points 99 and 100) swapped.
  std::vector<std::string> swapped = rows;
  std::swap(swapped[100], swapped[101]);
  expect_error({"--edge", write_edge("swapped.csv", swapped), "--features", features},
               {"swapped.csv: point 100 (", "not in measuring order"});
  // A gap: 20 points (~100 mm) removed; a larger --max-gap accepts it.
  std::vector<std::string> gap = rows;
  gap.erase(gap.begin() + 200, gap.begin() + 220);
  expect_error({"--edge", write_edge("gap.csv", gap), "--features", features},
               {"gap.csv: point 199 (", "a gap larger than 50 mm"});
  const auto ok = conform_run({"profile", "--edge", dir.file("gap.csv"), "--features", features, "--max-gap", "150"});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  // Fewer than 4 points.
  expect_error({"--edge", write_edge("three.csv", {rows[0], rows[1], rows[2], rows[3]}), "--features", features},
               {"three.csv: 3 edge points; at least 4"});
  // Ty beyond the measured edge.
  test::write_bytes(dir.file("far.csv"), "id,type,tx_mm,ty_mm,radius_mm\nH9,circle,100,2990,50\n");
  expect_error({"--edge", edge, "--features", dir.file("far.csv")},
               {"far.csv:2: feature 'H9' (circle) reaches Ty = 3040.000 mm", "beyond the measured edge"});
  // A number JSON cannot hold: exit 2 naming the file, never an internal error (the other feature checks:
  // ProfilePipeline.AbsurdUnitsAndOffTheWebFeaturesAreRefused).
  test::write_bytes(dir.file("huge.json"),
                    "{\"features\": [{\"id\": \"H1\", \"type\": \"point\", \"tx_mm\": 1e400, \"ty_mm\": 1}]}");
  expect_error({"--edge", edge, "--features", dir.file("huge.json")}, {"huge.json: not valid JSON", "1e400"});
  // Bad flags.
  expect_error({"--edge", edge, "--features", features, "--web-normal", "0,0"}, {"--web-normal"});
  EXPECT_EQ(conform_run({"profile", "--edge", edge, "--features", features, "--model", "quintic"}).exit_code, 2);
}

TEST(ProfileCommand, SpreadsheetEdgeFilesAndTheReversedDirection) {
  test::TempDir dir;
  const std::string edge = make_profile(dir, "p.csv");
  const std::string features = dir.file("p.features.csv");
  const auto base = conform_run({"profile", "--edge", edge, "--features", features, "--out", dir.file("a.csv")});
  ASSERT_EQ(base.exit_code, 0) << base.err;
  // BOM, upper-case names, semicolons, CRLF: the same result.
  std::vector<std::string> rows = lines(test::read_bytes(edge));
  std::string text = "\xEF\xBB\xBFX_MM;Y_MM;Z_MM\r\n";
  for (std::size_t k = 1; k < rows.size(); ++k) {
    std::string row = rows[k];
    std::replace(row.begin(), row.end(), ',', ';');
    text += row + "\r\n";
  }
  test::write_bytes(dir.file("excel.csv"), text);
  const auto excel =
      conform_run({"profile", "--edge", dir.file("excel.csv"), "--features", features, "--out", dir.file("b.csv")});
  ASSERT_EQ(excel.exit_code, 0) << excel.err;
  EXPECT_EQ(test::read_bytes(dir.file("b.csv")), test::read_bytes(dir.file("a.csv")));
  // Listed from the far end: --direction reverse gives the same holes (to the last point's noise).
  std::string reversed = rows[0] + "\n";
  for (std::size_t k = rows.size() - 1; k >= 1; --k) reversed += rows[k] + "\n";
  test::write_bytes(dir.file("reversed.csv"), reversed);
  const auto back = conform_run({"profile", "--edge", dir.file("reversed.csv"), "--features", features, "--direction",
                                 "reverse", "--out", dir.file("c.csv")});
  ASSERT_EQ(back.exit_code, 0) << back.err;
  EXPECT_LT(worst_centre_error(test::read_bytes(dir.file("c.csv")), test::read_bytes(dir.file("p.truth.csv"))), 0.3);
  // The fitted plane only on request, with the web source in JSON.
  const auto plane = conform_run({"profile", "--edge", edge, "--features", features, "--web-plane", "--json"});
  ASSERT_EQ(plane.exit_code, 0) << plane.err;
  EXPECT_EQ(nlohmann::json::parse(plane.out)["web"], "fitted plane");
  const auto machine = conform_run({"profile", "--edge", edge, "--features", features, "--json"});
  const auto j = nlohmann::json::parse(machine.out);
  EXPECT_EQ(j["web"], "machine +z");
  EXPECT_EQ(j["edge_outliers"], 0);
  ASSERT_EQ(j["warnings"].size(), 1u);  // only the twist one edge cannot see, per feature in "features"
  EXPECT_NE(j["warnings"][0].get<std::string>().find("twist is not observed"), std::string::npos);
  for (const auto& f : j["features"]) EXPECT_EQ(f["warnings"].size(), 1u) << f["id"];
}

}  // namespace
}  // namespace conform
