// The realistic-variation matrix of global registration (`conform align --init fpfh`, issue 13): ten seeds of each
// case, any rotation, each run end to end (files in, verdict out). A case passes when no seed gives a wrong pose
// that is trusted (verdict "yes" or "check", exit 0): every seed is right within the stated bounds, or refused
// (verdict "no", exit 1). Right: within 1 degree and 1 mm at the scan's centroid (the question here is the global
// one, the right basin; fine accuracy is measured elsewhere). Each also states for how many seeds the coarse step
// must end in the right basin (the measured figure, a seed or two below it), so that a change that breaks the
// coarse step fails even when fine ICP's verdict refuses the result. The bounds hold on seed streams 0-2
// (CONFORM_MATRIX_STREAM=1 or 2 runs seeds 11-20 or 21-30; registration_test_util.h): CI runs stream 0.
//   - a machined workpiece (datasets/workpiece.h) against its golden-sample scan: partial scans of 30-80 % of its
//     length, ~0.2 mm noise, another frame (issue 13's 169-degree case, generated);
//   - the same with the reference 100 m from the origin (shop-frame coordinates);
//   - the same with 0.5 mm noise and 5 % outliers;
//   - the ribbed plate (datasets/ribbed_plate.h): sampling that leaves translation along the ribs weakly fixed;
//   - a cylinder patch (full symmetry: its axis shift and turn are free and must be reported, or refused);
//   - the boss plate (near-symmetry: must not pick the mirror pose with exit 0).
// Small clouds (a few thousand points): enough to exercise the logic, 3-5 s CPU a case in a release build (the
// cylinder on 3000 / 1500 points and the boss plate on 2.0 / 1.6 mm grids: the same verdicts as on 6000 / 2500 and
// 1.5 / 1.2 mm, at 3.4 s instead of ~6 s and 3.7 s instead of 4.5 s).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "boss_plate.h"
#include "conform/core/io.h"
#include "conform/core/random.h"
#include "conform/datasets/ribbed_boss_plate.h"
#include "conform/datasets/ribbed_plate.h"
#include "conform/datasets/workpiece.h"
#include "conform/pipelines/align/align.h"
#include "registration_test_util.h"
#include "temp_dir.h"

namespace conform {
namespace {

constexpr int kSeeds = 10;

// One trial: the reference (its frame), the scan (its frame), the truth T_ref_scan.
struct Trial {
  std::vector<Eigen::Vector3d> reference, scan;
  std::vector<Face> reference_faces;  // a mesh reference when not empty
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
};

// Whether an estimate is right: by default its rotation and the displacement of the scan's centroid.
using RightFn = std::function<bool(const Trial&, const AlignResult&)>;

struct Tally {
  int right = 0, refused = 0, wrong_accepted = 0;
  int start_right = 0;  // the coarse step's pose (where fine ICP started) within the bounds
  int honest = 0;       // seeds whose error is within 3 predicted std on every axis (error_in_std)
  // Seeds whose fit held no motion: the error along a held motion (a cylinder's turn about its axis) is the start's,
  // which no std covers, so honesty is judged on these only (`honest` counts among them).
  int judged = 0;
};

bool holds_a_motion(const AlignResult& r) {
  const auto& d = r.icp.degeneracy.eigen_directions;
  return std::any_of(d.begin(), d.end(), [](const ConstraintDirection& c) { return c.held; });
}

void write_points(const std::string& path, const std::vector<Eigen::Vector3d>& points) {
  Mesh mesh;
  mesh.vertices = points;
  WriteOptions options;
  options.double_precision = true;  // shop-frame coordinates keep their micrometres
  write_mesh(path, mesh, options);
}

// Rotation error (deg) and the error at the scan's centroid (mm).
std::pair<double, double> pose_errors(const Trial& t, const Eigen::Isometry3d& estimate) {
  const Eigen::Vector3d c = test::mean_point(t.scan);
  return {test::rotation_error_deg(estimate, t.truth), (estimate * c - t.truth * c).norm()};
}

// The error of the estimate in units of its predicted std, axis by axis (the covariance's coordinates: rotations
// about the reference axes through its centre, translations): the largest |e_i| / std_i. Honest: a few at most.
double error_in_std(const Trial& t, const AlignResult& r) {
  const DegeneracyReport& d = r.icp.degeneracy;
  const Eigen::Isometry3d E = r.icp.T_ref_scan * t.truth.inverse();
  const Eigen::AngleAxisd aa(E.linear());
  Eigen::Matrix<double, 6, 1> e;
  e << aa.angle() * aa.axis(), E * d.centre - d.centre;
  double worst = 0.0;
  for (int i = 0; i < 6; ++i) {
    if (d.std(i) > 0.0) worst = std::max(worst, std::abs(e(i)) / d.std(i));
  }
  return worst;
}

RightFn within(double max_deg, double max_mm) {
  return [max_deg, max_mm](const Trial& t, const AlignResult& r) {
    const auto [deg, mm] = pose_errors(t, r.icp.T_ref_scan);
    return deg < max_deg && mm < max_mm;
  };
}

struct Outcome {
  bool right = false, accepted = false;
  AlignResult result;
};

// One trial through `conform align --init fpfh` (files in, verdict out), printed on one line.
Outcome run_trial(const char* name, const Trial& t, int seed, const RightFn& right,
                  const std::function<void(AlignOptions&)>& adjust = nullptr) {
  test::TempDir dir;
  AlignOptions options;
  options.scan_path = dir.file("scan.ply");
  options.reference_path = dir.file("reference.ply");
  options.init = AlignInit::kFpfh;
  options.seed = static_cast<std::uint64_t>(seed);
  if (adjust) adjust(options);
  write_points(options.scan_path, t.scan);
  if (t.reference_faces.empty()) {
    write_points(options.reference_path, t.reference);
  } else {
    Mesh mesh;
    mesh.vertices = t.reference;
    mesh.faces = t.reference_faces;
    write_mesh(options.reference_path, mesh);
  }
  Outcome out;
  out.result = run_align(options);
  const AlignResult& r = out.result;
  out.accepted = r.verdict.trust != AlignTrust::kNo;
  out.right = right(t, r);
  const auto [deg, mm] = pose_errors(t, r.icp.T_ref_scan);
  std::string held;
  for (const ConstraintDirection& d : r.icp.degeneracy.eigen_directions) {
    if (!d.held) continue;
    held += " " + std::to_string(d.std_mm).substr(0, 6) + "mm/" +
            std::to_string(d.std_rad * 180.0 / M_PI).substr(0, 6) + "deg(" +
            std::to_string(d.relative_eigenvalue).substr(0, 8) + ")";
  }
  const auto [start_deg, start_mm] = pose_errors(t, r.T_start);
  for (const StartReport& o : r.coarse.ranking.starts) {
    if (o.best_only_share > 0.0 || o.only_share > 0.0) {
      held += " [" + o.label + " " + std::to_string(o.inlier_share).substr(0, 5) + " " +
              std::to_string(o.best_only_share).substr(0, 6) + "/" + std::to_string(o.only_share).substr(0, 6) + "]";
    }
  }
  const Vector6d& sd = r.icp.degeneracy.std;
  std::printf(
      "  %s seed %d: %s %s, %.3f deg %.3f mm (start %.3f deg %.3f mm), std %.3f deg %.3f mm, error %.1f "
      "std, pose std %.3f mm (asked %.3f), overlap %.2f, start '%s', %d iterations, noise %.3f, held%s: %s\n",
      name, seed, out.right ? "right" : "WRONG", out.accepted ? "accepted" : "refused", deg, mm, start_deg, start_mm,
      sd.head<3>().maxCoeff() * 180.0 / M_PI, sd.tail<3>().maxCoeff(), error_in_std(t, r), r.verdict.pose_std_mm,
      r.verdict.pose_tolerance_mm, r.verdict.overlap, r.start.c_str(), r.icp.iterations, r.icp.degeneracy.noise_mm,
      held.c_str(), r.verdict.summary.c_str());
  return out;
}

// Runs `kSeeds` trials made by `make` (seed 1..kSeeds, or another stream's: test::matrix_seed).
Tally run_matrix(const char* name, const std::function<Trial(int)>& make, const RightFn& right,
                 const std::function<void(AlignOptions&)>& adjust = nullptr) {
  Tally tally;
  for (int i = 1; i <= kSeeds; ++i) {
    const int seed = test::matrix_seed(i, kSeeds);
    const Trial t = make(seed);
    const Outcome o = run_trial(name, t, seed, right, adjust);
    AlignResult start = o.result;
    start.icp.T_ref_scan = o.result.T_start;
    tally.start_right += right(t, start);
    tally.right += o.right && o.accepted;
    tally.refused += !o.accepted;
    tally.wrong_accepted += !o.right && o.accepted;
    if (!holds_a_motion(o.result)) {
      ++tally.judged;
      tally.honest += error_in_std(t, o.result) <= 3.0;
    }
  }
  std::printf(
      "  %s: %d right, %d refused, %d wrong and accepted; coarse pose right %d; error within 3 std %d of %d "
      "(no motion held)\n",
      name, tally.right, tally.refused, tally.wrong_accepted, tally.start_right, tally.honest, tally.judged);
  return tally;
}

// The golden sample (the whole top) as reference in the part's frame moved by `T_ref_part`; a partial scan of
// 30-80 % of the length (the share stepping with the seed, the window placed at random) in a random frame.
Trial workpiece_trial(int seed, const Eigen::Isometry3d& T_ref_part, double noise_mm, double outliers) {
  Random random(static_cast<std::uint64_t>(300 + seed));
  WorkpieceOptions golden;
  golden.points = 8000;
  golden.noise_mm = noise_mm;
  golden.outlier_share = outliers;
  golden.seed = static_cast<std::uint64_t>(1000 + seed);
  WorkpieceOptions partial = golden;
  const double share = 0.3 + 0.5 * test::matrix_index(seed, kSeeds) / (kSeeds - 1);
  partial.x_from = random.uniform(0.0, 1.0 - share);
  partial.x_to = partial.x_from + share;
  partial.points = static_cast<std::size_t>(8000 * share);
  partial.seed = static_cast<std::uint64_t>(2000 + seed);
  const Eigen::Isometry3d T_part_scan = test::random_motion(random, M_PI, 300.0, Eigen::Vector3d::Zero()).inverse();
  Trial t;
  t.reference = test::transformed_points(workpiece_samples(golden), T_ref_part);
  t.scan = test::transformed_points(workpiece_samples(partial), T_part_scan.inverse());
  t.truth = T_ref_part * T_part_scan;
  return t;
}

// The workpiece cases run at the defaults: the accuracy asked of the pose is 2.7 times the scan's or the fit's noise,
// and against these noisy golden-sample clouds the predicted std carries the fit's bias measured by the
// inverse-consistency check and the normal model's spread (pipelines/src/align/align_consistency.h). Without the
// bias, 19 of the 60 noisy-case seeds over streams 0-2 ended wrong with exit 0 at the defaults; the errors reached
// 6-17 predicted std; without the model's spread the error was within 3 std on 101 of the 120 seeds (115 with it).
// `honest`: seeds whose error is within 3 std on every axis. The bounds are the least over streams 0, 1, 2
// (CONFORM_MATRIX_STREAM): a change that accepts no right pose, or makes the std overconfident, fails.

TEST(AlignMatrixWorkpiece, PartialScans) {
  const Tally t = run_matrix(
      "workpiece", [](int seed) { return workpiece_trial(seed, Eigen::Isometry3d::Identity(), 0.2, 0.0); },
      within(1.0, 1.0));
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_GE(t.start_right, 9);  // measured 10, 9, 9 on streams 0, 1, 2
  EXPECT_GE(t.right, 1);        // measured 5, 1, 2: the rest refused, none wrong
  EXPECT_GE(t.honest, 9);       // measured 10, 10, 9
}

// The golden sample in shop coordinates: 100 m from the origin, turned; the scan in the scanner's frame.
Eigen::Isometry3d shop_frame() {
  Eigen::Isometry3d T_shop_part = Eigen::Isometry3d::Identity();
  T_shop_part.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.1, 0.2, 1.0).normalized()).toRotationMatrix();
  T_shop_part.translation() = Eigen::Vector3d(96000.0, -25000.0, 1200.0);
  return T_shop_part;
}

TEST(AlignMatrixWorkpiece, ShopFrameCoordinates) {
  const Tally t = run_matrix(
      "shop frame", [](int seed) { return workpiece_trial(seed, shop_frame(), 0.2, 0.0); }, within(1.0, 1.0));
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_GE(t.start_right, 9);  // measured 10
  EXPECT_GE(t.right, 2);        // measured 5, 5, 2 on streams 0, 1, 2
  EXPECT_GE(t.honest, 9);       // measured 10, 10, 9
}

TEST(AlignMatrixWorkpiece, NoiseAndOutliers) {
  const Tally t = run_matrix(
      "noise and outliers", [](int seed) { return workpiece_trial(seed, Eigen::Isometry3d::Identity(), 0.5, 0.05); },
      within(1.0, 1.0));
  EXPECT_EQ(t.wrong_accepted, 0);
  // Measured 4 and 6 on two RANSAC streams (PCL's RANSAC: 8; 1 without the outlier removal); with conform's own FPFH
  // 5, 5, 5 on streams 0, 1, 2.
  EXPECT_GE(t.start_right, 3);
  EXPECT_GE(t.right, 3);   // measured 3, 4, 4
  EXPECT_GE(t.honest, 9);  // measured 10, 9, 10
}

// Seeds of stream 1 where the forward fit settled in a poorer minimum and the reverse fit (align_consistency.h)
// pointed to the right one: restarted there (pipelines/src/align/align.cpp, restart_at_reverse_fit), each ends
// right; the two that were right but refused are accepted, and the one that was wrong (1.4 deg, 1.4 mm: refused) is
// right. Without the restart: right and refused, right and refused, wrong and refused.
TEST(AlignMatrixWorkpiece, RestartsWhereTheReverseFitFitsBetter) {
  const auto restarted = [](const AlignResult& r) {
    return std::any_of(r.warnings.begin(), r.warnings.end(),
                       [](const std::string& w) { return w.find("fine ICP restarted there") != std::string::npos; });
  };
  const Outcome shop = run_trial("shop frame", workpiece_trial(13, shop_frame(), 0.2, 0.0), 13, within(1.0, 1.0));
  EXPECT_TRUE(shop.right && shop.accepted);
  EXPECT_TRUE(restarted(shop.result));
  for (const int seed : {13, 20}) {
    const Outcome noisy = run_trial("noise and outliers", workpiece_trial(seed, Eigen::Isometry3d::Identity(), 0.5, 0.05),
                                    seed, within(1.0, 1.0));
    EXPECT_TRUE(noisy.right) << seed;
    EXPECT_EQ(noisy.accepted, seed == 20) << seed;
    EXPECT_TRUE(restarted(noisy.result)) << seed;
  }
}

// A coarse profiler pitch: steep walls (0.3 mm run) under points ~2 mm apart, so that the walls, the only thing
// that fixes the in-plane motions, carry a handful of points each: weakly but really constrained.
TEST(AlignMatrixWorkpiece, SparseWalls) {
  const auto make = [](int seed) {
    Trial t = workpiece_trial(seed, Eigen::Isometry3d::Identity(), 0.2, 0.0);
    WorkpieceOptions sparse;
    sparse.ramp_mm = 0.3;
    sparse.points = 4000;
    sparse.seed = static_cast<std::uint64_t>(1000 + seed);
    t.reference = workpiece_samples(sparse);
    return t;
  };
  const Tally t = run_matrix("sparse walls", make, within(1.0, 1.0));
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_GE(t.start_right, 4);  // measured 5 (PCL's RANSAC: 6); with conform's own FPFH 6, 7, 5 on streams 0, 1, 2
  EXPECT_GE(t.honest, 8);       // measured 8, 10, 9; right and accepted 0, 1, 1
}

// Random points on a cylinder's side (axis z, centred), radius r, length l, over `arc` radians, with radial noise.
std::vector<Eigen::Vector3d> cylinder_points(double r, double l, double arc, std::size_t n, double noise,
                                             Random& random) {
  std::vector<Eigen::Vector3d> out(n);
  for (Eigen::Vector3d& p : out) {
    const double a = random.uniform(0.0, arc), z = random.uniform(-0.5 * l, 0.5 * l);
    const double rho = r + noise * random.normal();
    p = Eigen::Vector3d(rho * std::cos(a), rho * std::sin(a), z);
  }
  return out;
}

// Full symmetry: a 150-degree, 100 mm patch of a cylinder against the whole cylinder (r 40, 150 mm long). Right when
// the scan lies on the cylinder (its axis within 0.5 degrees, RMS radial error < 0.15 mm) and the axis shift and turn
// are reported as free; or refused.
TEST(AlignMatrixSymmetry, CylinderIsFreeOrRefused) {
  const auto make = [](int seed) {
    Random random(static_cast<std::uint64_t>(400 + seed));
    Trial t;
    t.reference = cylinder_points(40.0, 150.0, 2.0 * M_PI, 3000, 0.05, random);
    const Eigen::Isometry3d T_ref_scan = test::random_motion(random, M_PI, 200.0, Eigen::Vector3d::Zero());
    t.scan = test::transformed_points(cylinder_points(40.0, 100.0, 150.0 * test::kDeg, 1500, 0.05, random),
                                      T_ref_scan.inverse());
    t.truth = T_ref_scan;
    return t;
  };
  const RightFn on_cylinder = [](const Trial& t, const AlignResult& r) {
    double sum = 0.0;
    for (const Eigen::Vector3d& p : t.scan) {
      const Eigen::Vector3d q = r.icp.T_ref_scan * p;
      const double e = q.head<2>().norm() - 40.0;
      sum += e * e;
    }
    const double axis =
        std::abs((r.icp.T_ref_scan.linear() * t.truth.linear().transpose() * Eigen::Vector3d::UnitZ()).z());
    return std::sqrt(sum / static_cast<double>(t.scan.size())) < 0.15 && axis > std::cos(0.5 * test::kDeg) &&
           r.icp.degeneracy.directions.size() >= 2 && r.verdict.trust != AlignTrust::kYes;
  };
  const Tally t = run_matrix("cylinder", make, on_cylinder);
  EXPECT_EQ(t.wrong_accepted, 0);
  // Its coarse candidates differ along the free motions only: the same answer, reported with those motions free,
  // verdict "check" (before issue 13's rule: ambiguous, refused 10/10).
  // Measured 10, 9, 9 on streams 0, 1, 2 (with PCL's FPFH 7: the cluster-robust covariance bound made seed 4's axis
  // tilt loose at the default 0.01 deg).
  EXPECT_GE(t.right, 7);
}

// Near-symmetry: the boss plate (boss_plate.h) turned 180 degrees fits all but the boss. The mirror pose must not
// come out with exit 0.
TEST(AlignMatrixSymmetry, BossPlateNeverTheMirror) {
  const auto make = [](int seed) {
    Random random(static_cast<std::uint64_t>(100 + seed));
    Trial t;
    t.reference = test::boss_plate(2.0, 0.0);
    t.truth = test::random_motion(random, M_PI, 50.0, Eigen::Vector3d::Zero());
    std::vector<Eigen::Vector3d> scan = test::boss_plate(1.6, 0.5);
    for (Eigen::Vector3d& p : scan) p += 0.02 * Eigen::Vector3d(random.normal(), random.normal(), random.normal());
    t.scan = test::transformed_points(scan, t.truth.inverse());
    return t;
  };
  const Tally t = run_matrix("boss plate", make, within(1.0, 1.0));
  EXPECT_EQ(t.wrong_accepted, 0);
}

}  // namespace
}  // namespace conform

namespace conform {
namespace {

// Issue 13's mesh pair, smaller: a partial scan (the 65 % of the ribbed plate with a boss at x < 30 mm, 0.02 mm
// noise, ~20k points) in a random frame against the plate's height-field mesh (1 mm grid, 60k faces), coarse
// (FPFH) + fine at the defaults. Right: within 0.05 degrees and 0.05 mm at the scan's centroid (at this density the
// fine fit lands 0.001-0.011 deg and 0.004-0.03 mm off; the full-size pair's 0.005 deg / 0.01 mm is the bench's);
// otherwise refused. With the features at 1/30 of the reference's diagonal (8.3 mm voxels: the 6 mm ribs one voxel
// wide) the full-size pair's coarse step found no pose.
TEST(AlignMatrixBossPlateMesh, PartialScanAgainstMesh) {
  const auto make = [](int seed) {
    Random random(static_cast<std::uint64_t>(500 + seed));
    RibbedPlateOptions plate;
    plate.points = 30000;
    plate.seed = static_cast<std::uint64_t>(600 + seed);
    const Mesh mesh = ribbed_boss_plate_mesh(plate, 1.0);
    Trial t;
    t.reference = mesh.vertices;
    t.reference_faces = mesh.faces;
    t.truth = test::random_motion(random, M_PI, 50.0, Eigen::Vector3d::Zero());
    std::vector<Eigen::Vector3d> scan;
    for (const Eigen::Vector3d& p : ribbed_plate_samples(plate)) {
      if (p.x() < 30.0) scan.emplace_back(p.x(), p.y(), p.z() + ribbed_plate_boss_height(p.x(), p.y()));
    }
    t.scan = test::transformed_points(scan, t.truth.inverse());
    return t;
  };
  const Tally t = run_matrix("boss plate mesh", make, within(0.05, 0.05));
  EXPECT_EQ(t.wrong_accepted, 0);
  EXPECT_GE(t.right, 7);  // measured 9, 10, 9 on streams 0, 1, 2 (7, 8, 8 before the coarse stage sampled the mesh)
  EXPECT_GE(t.start_right, 9);  // measured 10, 10, 10; 0 with the features at 1/30 of the reference's diagonal
  // The mesh's rib walls are one chord of the grid each: the scan's wall points lie up to half a grid step off them,
  // and the fit's kernel saturates them. Measured 9, 10, 9 of 10 within 3 std on streams 0, 1, 2 (8 on stream 0 and
  // 46 of 60 on streams 0-5 when the saturated pairs counted as information in the covariance; 55 of 60 since).
  EXPECT_GE(t.honest, 9);
}

}  // namespace
}  // namespace conform
