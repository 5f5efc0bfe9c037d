// Fine ICP alone from random starts (seeded): up to 5 degrees and 5% of the part's size away from the truth, on the
// tube patch, the box part and the free-form surface, for every variant. Prints the success rate and the final
// errors per part and variant; asserts them.

#include <chrono>
#include <cstdio>

#include <gtest/gtest.h>

#include "conform/registration/icp.h"
#include "test_parts.h"

namespace conform {
namespace {

using test::kDeg;
using test::PartKind;

constexpr int kTrials = 8;

struct Bounds {
  double rotation_deg, translation_mm;  // a trial succeeds within these
  int min_successes;                    // of kTrials
};

// Success bounds: the right basin and an accurate fit. Point-to-point stops on the reference's 4 mm vertex lattice
// (its nearest-vertex distances are biased by the spacing), so it is judged by looser bounds.
Bounds bounds_for(IcpMethod method) {
  if (method == IcpMethod::kPointToPoint) return {0.5, 1.5, kTrials};
  return {0.05, 0.05, kTrials};
}

void run_part(PartKind kind) {
  const test::TestPart part = test::make_test_part(kind);
  const IcpReference reference(part.reference);
  for (IcpMethod method : {IcpMethod::kPointToPoint, IcpMethod::kPointToPlane, IcpMethod::kPointToSurface}) {
    Random random(2024);
    std::vector<double> rotations, translations;
    int successes = 0, iterations = 0;
    const Bounds bounds = bounds_for(method);
    const auto start = std::chrono::steady_clock::now();
    for (int trial = 0; trial < kTrials; ++trial) {
      const Eigen::Isometry3d truth = test::random_motion(random, 5.0 * kDeg, 0.05 * part.size_mm, part.centre);
      const std::vector<Eigen::Vector3d> scan = test::transformed_points(part.scan, truth.inverse());
      IcpOptions options;
      options.method = method;
      options.max_iterations = method == IcpMethod::kPointToPoint ? 100 : 50;
      options.max_correspondence_distance_mm = 0.15 * part.size_mm;
      const IcpResult r = icp(scan, reference, Eigen::Isometry3d::Identity(), options);
      const test::PoseError e = test::pose_error(part, r.T_ref_scan, truth);
      rotations.push_back(e.rotation_deg);
      translations.push_back(e.translation_mm);
      iterations += r.iterations;
      successes += r.converged && e.rotation_deg < bounds.rotation_deg && e.translation_mm < bounds.translation_mm;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const test::Spread rot = test::spread_of(rotations), tra = test::spread_of(translations);
    std::printf(
        "  %-10s %-16s success %d/%d  rotation median %.4f max %.4f deg  translation median %.4f max %.4f mm"
        "  %.1f iterations  %.0f ms/trial\n",
        part.name.c_str(), to_string(method), successes, kTrials, rot.median, rot.max, tra.median, tra.max,
        static_cast<double>(iterations) / kTrials, ms / kTrials);
    EXPECT_GE(successes, bounds.min_successes) << part.name << " " << to_string(method);
  }
}

TEST(FinePerturbationMatrix, TubePatch) { run_part(PartKind::kTubePatch); }
TEST(FinePerturbationMatrix, BoxPart) { run_part(PartKind::kBox); }
TEST(FinePerturbationMatrix, FreeformSurface) { run_part(PartKind::kFreeform); }

}  // namespace
}  // namespace conform
