// The chord error estimated from a mesh alone (evaluation/chord_error.h) against the sagitta of known tessellations:
// a block with R10 fillets in 4 chords (CAD's coarse export) and in 64, a closed tube, and a scanner-like tube mesh
// whose noise must not read as chord error.

#include "conform/evaluation/chord_error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "conform/core/constants.h"
#include "conform/datasets/tube.h"
#include "test_meshes.h"

namespace conform {
namespace {

double sagitta(double radius_mm, double chord_angle_rad) { return radius_mm * (1.0 - std::cos(chord_angle_rad / 2)); }

// Fillet faces get the chords' sagitta within 2 % (0.3 % measured: phi h / 8 is its first order; the faces next to
// the flat sides see half the chord angle there, the median of their neighbours the full one); every flat face 0.
TEST(ChordError, FilletedBlockGivesItsChordsSagitta) {
  for (int chords : {4, 64}) {
    const Mesh block = test::filleted_block(60, 40, 20, 10, chords);
    const ChordErrorEstimate e = estimate_chord_error(block);
    const double truth = sagitta(10.0, kPi / 2 / chords);
    double fillet_min = 1e9, fillet_max = 0.0, flat_max = 0.0;
    for (std::size_t f = 0; f < block.faces.size(); ++f) {
      const Eigen::Vector3d n = face_normal(block, f);
      const bool flat = std::abs(n.z()) > 0.5 || std::abs(n.x()) > 1.0 - 1e-12 || std::abs(n.y()) > 1.0 - 1e-12;
      if (flat) {
        flat_max = std::max(flat_max, e.sagitta_mm[f]);
      } else {
        fillet_min = std::min(fillet_min, e.sagitta_mm[f]);
        fillet_max = std::max(fillet_max, e.sagitta_mm[f]);
      }
    }
    std::printf("%2d chords (sagitta %.5f mm): fillet faces %.5f..%.5f mm, flat faces up to %.3g\n", chords, truth,
                fillet_min, fillet_max, flat_max);
    EXPECT_EQ(flat_max, 0.0);
    EXPECT_NEAR(fillet_min, truth, 0.02 * truth);
    EXPECT_NEAR(fillet_max, truth, 0.02 * truth);
    const ChordErrorSummary s = summarize_chord_error(block, e, 0.025);  // half a +-0.05 mm tolerance
    if (chords == 4) {
      EXPECT_EQ(s.faces_over, 32u);  // 4 fillets x 4 chords x 2 triangles
      EXPECT_NEAR(s.area_over_mm2, 4 * 20 * 4 * 2 * 10 * std::sin(kPi / 16), 1e-6);
    } else {
      EXPECT_EQ(s.faces_over, 0u);
    }
  }
}

// A scanner-like mesh: a tube R 20 mm, 0.5 mm edges, 0.02 mm of noise along the normal (true sagitta 0.0016 mm).
// Noise bends every edge at random: about 0.3 sigma per face, the median over each face's neighbours keeps the tail
// below 0.9 sigma (0.0156 mm measured), under half a +-0.05 mm tolerance. Without noise, the staggered triangles (half
// as wide across the curve as an edge where an edge runs along the axis) give 0.00078 mm, half an edge's sagitta.
TEST(ChordError, NoiseIsNotTakenForCoarseFacets) {
  for (double noise : {0.0, 0.02}) {
    TubeOptions t;
    t.radius_mm = 20.0;
    t.length_mm = 60.0;
    t.edge_mm = 0.5;
    t.noise_mm = noise;
    t.seed = 3;
    const Mesh tube = generate_tube(t).mesh;
    const ChordErrorEstimate e = estimate_chord_error(tube);
    const ChordErrorSummary s = summarize_chord_error(tube, e, 0.025);
    std::printf("tube R 20, 0.5 mm edges, noise %.2f mm: estimated up to %.5f mm, %zu faces over 0.025 mm\n", noise,
                s.max_mm, s.faces_over);
    EXPECT_EQ(s.faces_over, 0u);
    if (noise == 0.0) {
      const double edge_sagitta = 0.5 * 0.5 / (8 * 20.0);
      EXPECT_LT(s.max_mm, 1.5 * edge_sagitta);
      EXPECT_GT(s.max_mm, 0.4 * edge_sagitta);
    }
  }
}

}  // namespace
}  // namespace conform
