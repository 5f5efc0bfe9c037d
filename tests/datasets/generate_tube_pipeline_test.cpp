#include "conform/pipelines/generate/generate_tube.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "conform/core/error.h"
#include "conform/core/io.h"
#include "temp_dir.h"

namespace conform {
namespace {

GenerateTubeOptions small_patch(const std::string& out_path) {
  GenerateTubeOptions options;
  options.out_path = out_path;
  options.tube.radius_mm = 150.0;
  options.tube.length_mm = 100.0;
  options.tube.arc_rad = M_PI / 2;
  options.tube.edge_mm = 5.0;
  options.tube.ovality_mm = 0.3;
  options.tube.seam_height_mm = 0.2;
  options.tube.noise_mm = 0.02;
  options.tube.outlier_fraction = 0.01;
  options.tube.random_holes = 1;
  options.tube.seed = 9;
  return options;
}

TEST(GenerateTubePipeline, WritesTheMeshAndItsTruthBeside) {
  test::TempDir dir;
  const GenerateTubeResult result = run_generate_tube(small_patch(dir.file("patch.ply")));
  EXPECT_EQ(result.truth_path, dir.file("patch.truth.json"));
  EXPECT_EQ(dir.listing(), "patch.ply\npatch.truth.json\n");

  const Mesh mesh = read_mesh(result.mesh_path);
  EXPECT_EQ(mesh.vertices.size(), result.vertices);
  EXPECT_EQ(mesh.faces.size(), result.faces);

  const nlohmann::json truth = nlohmann::json::parse(test::read_bytes(result.truth_path));
  EXPECT_EQ(truth, result.truth);
  EXPECT_EQ(truth["seed"], 9);
  EXPECT_EQ(truth["mesh_file"], "patch.ply");
  EXPECT_DOUBLE_EQ(truth["geometry"]["radius_mm"].get<double>(), 150.0);
  EXPECT_DOUBLE_EQ(truth["geometry"]["arc_deg"].get<double>(), 90.0);
  EXPECT_DOUBLE_EQ(truth["deformations"]["ovality"]["amplitude_mm"].get<double>(), 0.3);
  EXPECT_EQ(truth["mesh"]["vertices"], result.vertices);
  EXPECT_EQ(truth["scanner"]["outliers"]["indices"].size(), result.outliers);
  EXPECT_EQ(truth["scanner"]["holes"].size(), 1u);
  EXPECT_EQ(truth["geometry"]["axis_direction"], nlohmann::json::array({0.0, 0.0, 1.0}));
}

TEST(GenerateTubePipeline, SameOptionsGiveTheSameBytes) {
  test::TempDir dir;
  for (Encoding encoding : {Encoding::kBinary, Encoding::kAscii}) {
    for (const char* name : {"a.ply", "b.ply", "a.stl", "b.stl"}) {
      GenerateTubeOptions options = small_patch(dir.file(name));
      options.encoding = encoding;
      run_generate_tube(options);
    }
    EXPECT_EQ(test::read_bytes(dir.file("a.ply")), test::read_bytes(dir.file("b.ply")));
    EXPECT_EQ(test::read_bytes(dir.file("a.stl")), test::read_bytes(dir.file("b.stl")));
    EXPECT_FALSE(test::read_bytes(dir.file("a.ply")).empty());
    // The truth differs only by the mesh file's name.
    nlohmann::json a = nlohmann::json::parse(test::read_bytes(dir.file("a.truth.json")));
    nlohmann::json b = nlohmann::json::parse(test::read_bytes(dir.file("b.truth.json")));
    a.erase("mesh_file");
    b.erase("mesh_file");
    EXPECT_EQ(a.dump(), b.dump());
  }
}

TEST(GenerateTubePipeline, ABadExtensionIsAnErrorAndLeavesNoFile) {
  test::TempDir dir;
  for (const char* name : {"tube.obj", "tube.xyz", "tube"}) {
    try {
      run_generate_tube(small_patch(dir.file(name)));
      ADD_FAILURE() << name << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(dir.file(name)), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(dir.listing(), "");
}

TEST(GenerateTubePipeline, WhenTheTruthCannotBeWrittenTheMeshIsRemoved) {
  test::TempDir dir;
  std::filesystem::create_directory(dir.file("tube.truth.json"));  // a directory where the truth should go
  EXPECT_THROW(run_generate_tube(small_patch(dir.file("tube.ply"))), Error);
  EXPECT_EQ(dir.listing(), "tube.truth.json\n");
}

TEST(GenerateTubePipeline, InvalidTubeOptionsAreRejectedBeforeAnythingIsWritten) {
  test::TempDir dir;
  GenerateTubeOptions options = small_patch(dir.file("tube.ply"));
  options.tube.radius_mm = -1.0;
  try {
    run_generate_tube(options);
    ADD_FAILURE() << "negative radius accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("radius"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.listing(), "");
  EXPECT_EQ(tube_truth_path("/x/y/scan.PLY"), "/x/y/scan.truth.json");
}

}  // namespace
}  // namespace conform
