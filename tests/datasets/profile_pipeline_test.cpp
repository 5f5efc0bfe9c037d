// The profile pipelines: `generate profile` writes the files `profile` reads; the readers of edge and feature files.

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conform/core/error.h"
#include "conform/pipelines/generate/generate_profile.h"
#include "conform/pipelines/profile/profile.h"
#include "temp_dir.h"

namespace conform {
namespace {

GenerateProfileOptions small(const std::string& out) {
  GenerateProfileOptions o;
  o.scan.deformation.length_mm = 2400.0;
  o.scan.holes = 2;
  o.scan.marking_line = true;
  o.scan.second_edge = true;
  o.scan.seed = 3;
  o.out_path = out;
  return o;
}

std::string error_of(const std::string& features_path) {
  try {
    read_profile_features(features_path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ProfilePipeline, GeneratedFilesRoundTripThroughTheCompensation) {
  test::TempDir dir;
  const GenerateProfileResult g = run_generate_profile(small(dir.file("p.csv")));
  EXPECT_EQ(dir.listing(), "p.csv\np.edge2.csv\np.features.csv\np.truth.csv\np.truth.json\n") << dir.listing();
  const nlohmann::json truth = nlohmann::json::parse(test::read_bytes(g.truth_json_path));
  EXPECT_EQ(truth["edge_file"], "p.csv");
  EXPECT_EQ(truth["length_mm"], 2400.0);
  EXPECT_EQ(truth["seed"], 3);

  ProfileJobOptions job;
  job.edge_path = g.edge_path;
  job.features_path = g.features_path;
  job.second_edge_path = g.second_edge_path;
  job.out_path = dir.file("out.csv");
  const ProfileJobResult r = run_profile(job);
  ASSERT_TRUE(r.compensation.ok);
  EXPECT_EQ(r.edge_points, g.edge_points);
  ASSERT_EQ(r.compensation.features.size(), 3u);  // H1, H2, M1
  EXPECT_EQ(r.compensation.features[2].type, ProfileFeatureType::kPolyline);
  const std::string csv = test::read_bytes(job.out_path);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "id,i,tx_mm,ty_mm,x_mm,y_mm,z_mm,nx,ny,nz,dx,dy,dz");
  EXPECT_EQ(csv.substr(csv.find('\n') + 1, 6), "H1,-1,");  // the centre first
  EXPECT_EQ(csv, profile_csv(r.compensation));
  // Rerun: the same bytes.
  const GenerateProfileResult again = run_generate_profile(small(dir.file("q.csv")));
  EXPECT_EQ(test::read_bytes(again.edge_path), test::read_bytes(g.edge_path));
  EXPECT_EQ(test::read_bytes(again.truth_path), test::read_bytes(g.truth_path));
}

TEST(ProfilePipeline, ReadsFeaturesFromCsvAndJson) {
  test::TempDir dir;
  test::write_bytes(dir.file("f.csv"),
                    "# designed features\nid,type,tx_mm,ty_mm,radius_mm\nA,point,10,20,\nB,circle,100,500,50\n"
                    "S,slot,100,700,20\nS,slot,100,800,20\nL,polyline,0,0,\nL,polyline,5,100,\nL,polyline,5,200,\n");
  const std::vector<ProfileFeature> csv = read_profile_features(dir.file("f.csv"));
  ASSERT_EQ(csv.size(), 4u);
  EXPECT_EQ(csv[2].vertices.size(), 2u);
  EXPECT_EQ(csv[3].vertices.size(), 3u);
  EXPECT_DOUBLE_EQ(csv[1].radius_mm, 50.0);
  EXPECT_EQ(csv[1].where, dir.file("f.csv") + ":4");
  test::write_bytes(dir.file("f.json"),
                    R"({"features": [{"id": "A", "type": "point", "tx_mm": 10, "ty_mm": 20},
                                     {"id": "B", "type": "circle", "tx_mm": 100, "ty_mm": 500, "radius_mm": 50},
                                     {"id": "P", "type": "polygon", "points_mm": [[0, 0], [50, 0], [50, 80]]}]})");
  const std::vector<ProfileFeature> json = read_profile_features(dir.file("f.json"));
  ASSERT_EQ(json.size(), 3u);
  EXPECT_EQ(json[2].type, ProfileFeatureType::kPolygon);
  EXPECT_EQ(json[2].vertices[2], Eigen::Vector2d(50.0, 80.0));
}

TEST(ProfilePipeline, FeatureErrorsNameTheFileAndLine) {
  test::TempDir dir;
  test::write_bytes(dir.file("a.csv"), "id,type,tx_mm,ty_mm,radius_mm\nA,ellipse,1,2,3\n");
  EXPECT_NE(error_of(dir.file("a.csv")).find("a.csv:2: unknown feature type 'ellipse'"), std::string::npos);
  test::write_bytes(dir.file("b.csv"), "id,type,tx_mm,ty_mm,radius_mm\nA,point,1,2,\nB,point,1,2,\nA,point,3,4,\n");
  EXPECT_NE(error_of(dir.file("b.csv")).find("b.csv:4: id 'A' comes back"), std::string::npos);
  test::write_bytes(dir.file("c.csv"), "id,type,tx_mm,ty_mm\nA,circle,1,2\n");
  EXPECT_NE(error_of(dir.file("c.csv")).find("needs the column radius_mm"), std::string::npos);
  test::write_bytes(dir.file("d.json"), R"({"features": [{"id": "A", "type": "circle", "tx_mm": 1, "ty_mm": 2}]})");
  EXPECT_NE(error_of(dir.file("d.json")).find("features[0]: 'radius_mm' must be a number"), std::string::npos);
  test::write_bytes(dir.file("e.json"), "{oops");
  EXPECT_NE(error_of(dir.file("e.json")).find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of(dir.file("f.txt")).find("from .csv or .json"), std::string::npos);
}

// run_profile's message for the features in `text` against a generated 2.4 m edge (empty when it runs).
std::string job_error(const test::TempDir& dir, const std::string& name, const std::string& text,
                      double web_width_mm = 0.0) {
  test::write_bytes(dir.file(name), text);
  ProfileJobOptions job;
  job.edge_path = dir.file("p.csv");
  job.features_path = dir.file(name);
  job.compensation.web_width_mm = web_width_mm;
  try {
    run_profile(job);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ProfilePipeline, AbsurdUnitsAndOffTheWebFeaturesAreRefused) {
  test::TempDir dir;
  run_generate_profile(small(dir.file("p.csv")));
  const std::string header = "id,type,tx_mm,ty_mm,radius_mm\n";
  // Beyond +-1e7: refused where the table is read (core/csv.h), naming the line and the column.
  EXPECT_NE(job_error(dir, "huge.csv", header + "H1,circle,9e18,100,5\n").find("huge.csv:2: column 'tx_mm'"),
            std::string::npos);
  EXPECT_NE(job_error(dir, "e300.csv", header + "H1,circle,1e300,100,5\n").find("beyond"), std::string::npos);
  EXPECT_NE(job_error(dir, "far.csv", header + "H1,circle,9e6,100,5\n").find("far.csv:2: feature 'H1'"),
            std::string::npos);
  EXPECT_NE(job_error(dir, "big.json", R"({"features": [{"id": "A", "type": "point", "tx_mm": 1e400, "ty_mm": 1}]})")
                .find("not valid JSON"),
            std::string::npos);
  EXPECT_NE(job_error(dir, "m.csv", header + "H1,circle,0.1,1.2,0.05\n").find("are the features in metres?"),
            std::string::npos);
  EXPECT_NE(job_error(dir, "off.csv", header + "H1,circle,-200,1200,50\n").find("reaches Tx = -250.000 mm"),
            std::string::npos);
  EXPECT_NE(job_error(dir, "wide.csv", header + "H1,circle,1000,1200,50\n", 370.0)
                .find("reaches Tx = 1050.000 mm, beyond the web's width of 370.000 mm"),
            std::string::npos);
  EXPECT_EQ(job_error(dir, "fine.csv", header + "H1,circle,100,1200,50\n", 370.0), "");
}

TEST(ProfilePipeline, NothingWrittenOnBadOptions) {
  test::TempDir dir;
  GenerateProfileOptions o = small(dir.file("p.csv"));
  o.scan.spacing_mm = -1.0;
  EXPECT_THROW(run_generate_profile(o), Error);
  o = small(dir.file("p.ply"));
  EXPECT_THROW(run_generate_profile(o), Error);
  EXPECT_EQ(dir.listing(), "");
}

}  // namespace
}  // namespace conform
