// A generated tube patch with a bump against the same tube without it: the deviation of every scan vertex is the
// bump's height there (the generator's truth: r(theta, z) - R), up to the reference's faceting, and the largest
// deviation is the bump's height.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/datasets/tube.h"
#include "conform/evaluation/deviation.h"
#include "conform/evaluation/statistics.h"

namespace conform {
namespace {

TubeOptions patch(double edge_mm) {
  TubeOptions t;
  t.radius_mm = 100.0;
  t.length_mm = 120.0;
  t.arc_rad = kPi / 3;
  t.edge_mm = edge_mm;
  return t;
}

void check_bump(double height_mm) {
  TubeOptions scan_options = patch(1.0);
  scan_options.bumps.push_back({0.1, 5.0, height_mm, 25.0});
  const TubeScan scan = generate_tube(scan_options);
  const TubeOptions reference_options = patch(0.5);
  const TubeScan reference = generate_tube(reference_options);

  DeviationOptions flat;  // the faceting bound below is the flat facets'
  flat.smooth_surface = false;
  const DeviationResult d = compute_deviation(scan.mesh.vertices, reference.mesh, flat);
  ASSERT_EQ(d.matched, scan.mesh.vertices.size());
  // The reference's triangles are chords of the cylinder: they lie inside it by at most R (1 - cos(step / 2)), where
  // step is the azimuth one triangle spans (about edge^2 / (8 R)).
  const double sagitta = reference_options.radius_mm * (1.0 - std::cos(0.5 * reference.truth.grid.column_step_rad));
  double truth_extreme = 0.0;
  for (std::size_t i = 0; i < d.deviation_mm.size(); ++i) {
    const Eigen::Vector2d& tz = scan.truth.vertex_parameters[i];
    const double truth = tube_radius(scan_options, tz.x(), tz.y()) - tube_radius(reference_options, tz.x(), tz.y());
    ASSERT_GE(d.deviation_mm[i], truth - 1e-9) << "vertex " << i;
    ASSERT_LE(d.deviation_mm[i], truth + sagitta + 1e-9) << "vertex " << i;
    if (std::abs(truth) > std::abs(truth_extreme)) truth_extreme = truth;
  }
  const DeviationStatistics s = deviation_statistics(d.deviation_mm);
  const double extreme = height_mm > 0 ? s.max_mm : s.min_mm;
  std::printf("bump %+.3f mm: measured %s %.6f mm, largest truth over the vertices %.6f mm, faceting <= %.6f mm\n",
              height_mm, height_mm > 0 ? "max" : "min", extreme, truth_extreme, sagitta);
  EXPECT_NEAR(extreme, truth_extreme, sagitta + 1e-9);
  // The vertex nearest the bump's top is within half an edge of it: the raised cosine has dropped < 0.3 % there.
  EXPECT_NEAR(extreme, height_mm, 0.003 * std::abs(height_mm) + sagitta);
}

TEST(TubeBump, TheLargestDeviationIsTheBumpsHeight) { check_bump(2.0); }

TEST(TubeBump, AnIndentationIsTheSmallestDeviation) { check_bump(-1.5); }

}  // namespace
}  // namespace conform
