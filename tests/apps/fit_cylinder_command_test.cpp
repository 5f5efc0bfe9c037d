// `conform fit-cylinder` end to end: a generated tube scan fitted through the real executable (exit 0, the JSON keys
// of issue 4, figures against the generator's truth), the residuals CSV, a plane scan (exit 1, "not a cylinder"),
// and bad input (exit 2, naming the file or the option).

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

test::RunResult conform_run(std::vector<std::string> args) { return test::run(CONFORM_EXE, args); }

test::RunResult fit(std::vector<std::string> args) {
  args.insert(args.begin(), "fit-cylinder");
  return conform_run(args);
}

// A 120 deg patch of a 150 mm tube on a tilted axis, 20k vertices, sigma 0.1 mm, 10% outliers.
std::string generated_patch(const test::TempDir& dir) {
  const std::string path = dir.file("patch.ply");
  const auto r =
      conform_run({"generate",         "tube",  "--out",   path,  "--radius",   "150", "--arc-deg",    "120",
                   "--vertices",       "20000", "--noise", "0.1", "--outliers", "0.1", "--axis-point", "100,-50,20",
                   "--axis-direction", "0,1,1", "--seed",  "3",   "--quiet"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return path;
}

TEST(FitCylinderCommand, FitsAGeneratedPatchAndPrintsTheJsonKeys) {
  test::TempDir dir;
  const std::string path = generated_patch(dir);
  const auto r = fit({"--input", path, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // one JSON object and nothing else on stdout
  for (const char* key :
       {"axis_point_mm", "axis_direction", "radius_mm", "rms_mm", "inlier_fraction", "radius_std_mm"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["ok"], true);
  EXPECT_EQ(j["normals"], "pca (mesh faces)");
  EXPECT_EQ(j["side"], "outer");
  const double radius = j["radius_mm"].get<double>();
  EXPECT_NEAR(radius, 150.0, 4.0 * j["radius_std_mm"].get<double>() + 1e-4);  // + the .ply's float coordinates
  const std::vector<double> a = j["axis_direction"].get<std::vector<double>>();
  EXPECT_NEAR(std::abs(a[1] + a[2]) / std::sqrt(2.0), 1.0, 1e-6);  // along (0, 1, 1), either sign
  const std::vector<double> c = j["axis_point_mm"].get<std::vector<double>>();
  // The axis point lies on the line through (100, -50, 20) along (0, 1, 1).
  EXPECT_NEAR(c[0], 100.0, 0.05);
  EXPECT_NEAR((c[1] + 50.0) - (c[2] - 20.0), 0.0, 0.05);
  EXPECT_NEAR(j["inlier_fraction"].get<double>(), 0.9, 0.01);
  EXPECT_NEAR(j["rms_mm"].get<double>(), 0.1, 0.01);
  EXPECT_NEAR(j["arc_deg"].get<double>(), 120.0, 1.0);

  const auto text = fit({"--input", path, "--quiet"});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("result        cylinder"), std::string::npos) << text.out;
}

TEST(FitCylinderCommand, WritesTheResidualsCsv) {
  test::TempDir dir;
  const std::string path = generated_patch(dir);
  const std::string csv = dir.file("residuals.csv");
  const auto r = fit({"--input", path, "--out", csv, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  std::istringstream in(test::read_bytes(csv));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "i,x_mm,y_mm,z_mm,distance_mm,inlier");
  std::size_t rows = 0, inliers = 0;
  double sum_squares = 0.0;
  while (std::getline(in, line)) {
    ++rows;
    const std::size_t last = line.rfind(',');
    const double distance = std::stod(line.substr(line.rfind(',', last - 1) + 1));
    if (line.substr(last + 1) == "1") {
      ++inliers;
      sum_squares += distance * distance;
    }
  }
  EXPECT_EQ(rows, j["points"].get<std::size_t>());
  EXPECT_EQ(inliers, j["inliers"].get<std::size_t>());
  EXPECT_NEAR(std::sqrt(sum_squares / static_cast<double>(inliers)), j["rms_mm"].get<double>(), 1e-5);
}

TEST(FitCylinderCommand, APlaneIsNotACylinder) {
  test::TempDir dir;
  const std::string path = dir.file("plate.xyz");
  std::string text = "x y z\n";
  for (int i = 0; i < 60; ++i) {
    for (int k = 0; k < 40; ++k) {
      const double bump = 0.05 * std::sin(1.7 * i + 2.3 * k);  // scanner noise, ~0.035 mm RMS
      text += std::to_string(5.0 * i) + " " + std::to_string(5.0 * k) + " " + std::to_string(12.0 + bump) + "\n";
    }
  }
  test::write_bytes(path, text);
  const auto r = fit({"--input", path, "--quiet"});
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.err.find("not a cylinder"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("plane"), std::string::npos) << r.err;
  const auto json = fit({"--input", path, "--json"});
  EXPECT_EQ(json.exit_code, 1);
  const auto j = nlohmann::json::parse(json.out);
  EXPECT_EQ(j["ok"], false);
  EXPECT_EQ(j["failure"], "plane");
}

TEST(FitCylinderCommand, BadInputIsExitCodeTwoNamingTheProblem) {
  test::TempDir dir;
  const std::string missing = dir.file("missing.ply");
  auto r = fit({"--input", missing});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;

  const std::string broken = dir.file("broken.ply");
  test::write_bytes(broken, "ply\nformat ascii 1.0\nelement vertex 1000000\nproperty float x\nend_header\n1\n");
  r = fit({"--input", broken});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(broken), std::string::npos) << r.err;

  const std::string few = dir.file("few.xyz");
  test::write_bytes(few, "0 0 0\n1 0 0\n0 1 0\n");
  r = fit({"--input", few});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(few), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at least 6"), std::string::npos) << r.err;

  const std::string line = dir.file("line.xyz");
  std::string text;
  for (int i = 0; i < 20; ++i) text += std::to_string(i) + " " + std::to_string(2 * i) + " 0\n";
  test::write_bytes(line, text);
  r = fit({"--input", line});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line"), std::string::npos) << r.err;

  const std::string path = generated_patch(dir);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--input", path, "--threshold", "-1"},
        std::vector<std::string>{"--input", path, "--min-radius", "200", "--max-radius", "100"},
        std::vector<std::string>{"--input", path, "--axis", "0", "0", "0"},
        std::vector<std::string>{"--input", path, "--out", dir.file("r.txt")},
        std::vector<std::string>{"--threshold", "1"}}) {
    r = fit(args);
    EXPECT_EQ(r.exit_code, 2) << args.back() << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_EQ(test::read_bytes(dir.file("r.txt")), "");  // no partial output
}

}  // namespace
}  // namespace conform
