// A welded bracket scanned from one side (41 % of its surface; 0.03 mm noise) in six random frames (up to 180 deg,
// 100 mm away), `align --init fpfh` against its STEP and against a CAD-like STL exported from it (0.1 mm deflection:
// 288 triangles, its flat faces a few long thin triangles each): never a wrong pose with exit 0, and right to 0.01
// deg / 0.01 mm at the part where accepted. The coarse stage samples the reference's surface at the scan's spacing
// whatever the tessellation (a CAD-like STL once stalled it for 30-40 s); each run takes about a second.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <TopoDS_Shape.hxx>
#include <nlohmann/json.hpp>

#include "cad_shapes.h"
#include "conform/core/cad.h"
#include "conform/core/io.h"
#include "conform/core/random.h"
#include "run_command.h"
#include "temp_dir.h"

namespace conform {
namespace {

Eigen::Isometry3d transform_of(const nlohmann::json& j) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 4; ++col) T(row, col) = j["T_ref_scan"][row][col].get<double>();
  }
  return Eigen::Isometry3d(T);
}


// A turn of up to max_deg about a random axis and a shift of up to max_mm in a random direction.
Eigen::Isometry3d random_motion(Random& random, double max_deg, double max_mm) {
  const auto direction = [&random] {
    return Eigen::Vector3d(random.normal(), random.normal(), random.normal()).normalized();
  };
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(random.uniform(0.0, max_deg) * M_PI / 180.0, direction()));
  T.translation() = random.uniform(0.0, max_mm) * direction();
  return T;
}

// The scan: the exact surface's points whose outward normal faces the scanner (looking from +y, +z, a little +x at
// the inside of the bracket's corner), in the scanner's frame.
struct Scan {
  std::vector<Eigen::Vector3d> points;
  double share = 0.0;  // of the sample over the whole part
};

Scan scan_from_one_side(const TopoDS_Shape& part, const Eigen::Isometry3d& T_part_scan, std::uint64_t seed) {
  const test::SurfaceSample sample = test::sample_surface(part, 40000, 0.03, seed);
  const Eigen::Vector3d towards_scanner = Eigen::Vector3d(0.3, 0.7, 0.65).normalized();
  Scan scan;
  for (std::size_t i = 0; i < sample.points.size(); ++i) {
    if (sample.normals[i].dot(towards_scanner) > 0.3) scan.points.push_back(T_part_scan.inverse() * sample.points[i]);
  }
  scan.share = static_cast<double>(scan.points.size()) / static_cast<double>(sample.points.size());
  return scan;
}

// `align --init fpfh --json` of the scan (written to scan.ply in `dir`) against `reference`, and its pose's error: the
// turn, and the displacement of the part's `centre`.
struct AlignRun {
  int exit_code = 0;
  std::string trust, start;
  double rotation_deg = 0.0;
  double translation_mm = 0.0;
};

AlignRun align_scan(const test::TempDir& dir, const Scan& scan, const std::string& reference,
                    const Eigen::Isometry3d& T_part_scan, const Eigen::Vector3d& centre) {
  Mesh cloud;
  cloud.vertices = scan.points;
  WriteOptions write;
  write.double_precision = true;
  write_mesh(dir.file("scan.ply"), cloud, write);
  const test::RunResult r = test::run(
      CONFORM_EXE, {"align", "--scan", dir.file("scan.ply"), "--reference", reference, "--init", "fpfh", "--json"});
  AlignRun out;
  out.exit_code = r.exit_code;
  if (r.exit_code == 2) {
    ADD_FAILURE() << reference << ": " << r.err;
    return out;
  }
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const Eigen::Isometry3d error = T_part_scan.inverse() * transform_of(j);
  out.rotation_deg = Eigen::AngleAxisd(error.rotation()).angle() * 180.0 / M_PI;
  const Eigen::Vector3d at = T_part_scan.inverse() * centre;
  out.translation_mm = (error * at - at).norm();
  out.trust = j["trust"].get<std::string>();
  out.start = j["start"].get<std::string>();
  return out;
}

TEST(CadBracket, ScannedFromOneSideCoarseAlignsAgainstStepAndCadLikeStl) {
  test::TempDir dir;
  const TopoDS_Shape bracket = test::welded_bracket();
  test::write_cad(bracket, dir.file("bracket.step"), test::CadFormat::kStep, "MM");
  // The CAD-like STL: the STEP tessellated coarsely (0.1 mm, 28.6 deg), as a CAD system exports it.
  CadReadOptions coarse;
  coarse.deflection_mm = 0.1;
  const Mesh stl = read_cad(dir.file("bracket.step"), coarse, nullptr, nullptr);
  write_mesh(dir.file("bracket.stl"), stl);
  std::printf("CAD-like STL: %zu vertices, %zu triangles\n", stl.vertices.size(), stl.faces.size());
  const Eigen::Vector3d centre(60, 30, 30);
  Random random(11);
  int right = 0, wrong_accepted = 0, runs = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const Eigen::Isometry3d T_part_scan = random_motion(random, 180.0, 100.0);
    const Scan scan = scan_from_one_side(bracket, T_part_scan, static_cast<std::uint64_t>(trial + 1));
    for (const char* reference : {"bracket.step", "bracket.stl"}) {
      const AlignRun r = align_scan(dir, scan, dir.file(reference), T_part_scan, centre);
      const bool ok = r.rotation_deg < 0.01 && r.translation_mm < 0.01;
      ++runs;
      right += ok && r.exit_code == 0;
      wrong_accepted += !ok && r.exit_code == 0;
      std::printf("trial %d (%.0f deg), %.0f %% scanned, %s: %.5f deg, %.5f mm, exit %d, trust %s\n", trial,
                  Eigen::AngleAxisd(T_part_scan.rotation()).angle() * 180.0 / M_PI, 100.0 * scan.share, reference,
                  r.rotation_deg, r.translation_mm, r.exit_code, r.trust.c_str());
    }
  }
  std::printf("%d runs: %d right and accepted, %d wrong and accepted\n", runs, right, wrong_accepted);
  EXPECT_EQ(wrong_accepted, 0);
  // Measured 12 of 12 (6 of 12 before the narrow FPFH support; 48 of 48 on 24 other frames, 35 before). Where it
  // failed, every FPFH hypothesis was the bracket turned 180 deg about its corner's diagonal or shifted by a plate's
  // thickness: at the default support (5 voxels, 19 mm) a reference histogram holds the far face of a 10 mm plate,
  // which a scan from one side never sees, so fewer than 50 features were mutual nearest neighbours and RANSAC drew
  // from every nearest-feature pair (2 % right). At 2.5 voxels over 200 are mutual, 2.5-11 % right
  // (docs/measurements/cad.md).
  EXPECT_EQ(right, 12);
}

// Plates thinner than the FPFH support (5 and 3 mm at a 19 mm support), scanned from one side, against their STEP: the
// features cannot tell a plate's faces apart and the starts land a wall off, so the coarse stage probes the poses
// shifted through the reference's walls (registration/thin_walls.h). These six runs before the probes: 2 right and
// accepted, 4 refused (turned 180 deg and 7.5 mm off, or 4.26 mm: a wall's diagonal); on 18 other runs (scripted)
// 6 right and 4 wrong and accepted, one with "trust the pose" 7.07 mm off; with the probes all right and accepted
// (docs/measurements/cad.md).
TEST(CadBracket, ThinPlatesScannedFromOneSideAreNotTakenAWallOff) {
  test::TempDir dir;
  const Eigen::Vector3d centre(60, 30, 30);
  Random random(13);
  int right = 0, wrong_accepted = 0, runs = 0;
  for (const double thickness : {5.0, 3.0}) {
    const TopoDS_Shape part = test::thin_plates(thickness);
    test::write_cad(part, dir.file("plates.step"), test::CadFormat::kStep, "MM");
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Isometry3d T_part_scan = random_motion(random, 180.0, 100.0);
      const Scan scan = scan_from_one_side(part, T_part_scan, static_cast<std::uint64_t>(trial + 1));
      const AlignRun r = align_scan(dir, scan, dir.file("plates.step"), T_part_scan, centre);
      const bool ok = r.rotation_deg < 0.01 && r.translation_mm < 0.05;
      ++runs;
      right += ok && r.exit_code == 0;
      wrong_accepted += !ok && r.exit_code == 0;
      std::printf("%.0f mm plates, trial %d: %.5f deg, %.5f mm, exit %d, trust %s, start %s\n", thickness, trial,
                  r.rotation_deg, r.translation_mm, r.exit_code, r.trust.c_str(), r.start.c_str());
    }
  }
  EXPECT_EQ(wrong_accepted, 0);
  EXPECT_EQ(right, runs);
}

}  // namespace
}  // namespace conform
