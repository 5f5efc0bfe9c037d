// Coarse + fine from random starts (seeded): up to 30 degrees and 20% of the part's size away from the truth, on
// the tube patch, the box part and the free-form surface, with principal axes and with FPFH + RANSAC, then
// point-to-plane ICP. Prints the success rate, the final errors and which starts won; asserts them.

#include <chrono>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "conform/registration/coarse.h"
#include "conform/registration/icp.h"
#include "test_parts.h"

namespace conform {
namespace {

using test::kDeg;
using test::PartKind;

// FPFH costs ~0.1-0.5 s a run (descriptors and RANSAC); PCA's starts ~50 ms.
int trials_for(CoarseMethod method) { return method == CoarseMethod::kFpfh ? 3 : 5; }

void run_part(PartKind kind, CoarseMethod method) {
  const int kTrials = trials_for(method);
  const test::TestPart part = test::make_test_part(kind);
  const IcpReference reference(part.reference);
  Random random(99);
  std::vector<double> rotations, translations;
  std::map<std::string, int> winners;
  int successes = 0, ambiguous = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Isometry3d truth = test::random_motion(random, 30.0 * kDeg, 0.2 * part.size_mm, part.centre);
    const std::vector<Eigen::Vector3d> scan = test::transformed_points(part.scan, truth.inverse());
    CoarseOptions coarse;
    coarse.method = method;
    coarse.multi_start.probe.max_correspondence_distance_mm = 0.1 * part.size_mm;
    coarse.fpfh.seed = static_cast<std::uint64_t>(trial + 1);
    const CoarseResult c = coarse_align(scan, reference, coarse);
    IcpOptions fine;
    fine.max_correspondence_distance_mm = 0.05 * part.size_mm;
    const IcpResult r = icp(scan, reference, c.T_ref_scan, fine);
    const test::PoseError e = test::pose_error(part, r.T_ref_scan, truth);
    rotations.push_back(e.rotation_deg);
    translations.push_back(e.translation_mm);
    ++winners[c.winner.substr(0, c.winner.find(' '))];
    ambiguous += c.ranking.ambiguous;
    successes += r.converged && e.rotation_deg < 0.05 && e.translation_mm < 0.05;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const test::Spread rot = test::spread_of(rotations), tra = test::spread_of(translations);
  std::string won;
  for (const auto& [label, count] : winners) won += " " + label + " x" + std::to_string(count);
  std::printf(
      "  %-10s %-5s success %d/%d  rotation median %.4f max %.4f deg  translation median %.4f max %.4f mm"
      "  ambiguous %d  won:%s  %.0f ms/trial\n",
      part.name.c_str(), to_string(method), successes, kTrials, rot.median, rot.max, tra.median, tra.max, ambiguous,
      won.c_str(), ms / kTrials);
  EXPECT_EQ(successes, kTrials) << part.name << " " << to_string(method);
}

TEST(CoarsePerturbationMatrix, TubePatchPca) { run_part(PartKind::kTubePatch, CoarseMethod::kPca); }
TEST(CoarsePerturbationMatrix, TubePatchFpfh) { run_part(PartKind::kTubePatch, CoarseMethod::kFpfh); }
TEST(CoarsePerturbationMatrix, BoxPartPca) { run_part(PartKind::kBox, CoarseMethod::kPca); }
TEST(CoarsePerturbationMatrix, BoxPartFpfh) { run_part(PartKind::kBox, CoarseMethod::kFpfh); }
TEST(CoarsePerturbationMatrix, FreeformPca) { run_part(PartKind::kFreeform, CoarseMethod::kPca); }
TEST(CoarsePerturbationMatrix, FreeformFpfh) { run_part(PartKind::kFreeform, CoarseMethod::kFpfh); }

}  // namespace
}  // namespace conform
