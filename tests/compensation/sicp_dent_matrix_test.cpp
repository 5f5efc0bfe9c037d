// Dents at the edge under noise (issue 30): whether a local shape change is caught must not hinge on the noise level.
// A dent 0.5-1.5 mm deep and 10-30 mm wide at the edge of the new panels' oval and cut-out and of the reduced nose
// cone's window (on their sides), scan noise 0.03-0.15 mm, three seeds (the dent at a different place on each): no
// dented path may be trusted beyond the bar (off the true path mean <= 0.2 mm, peak <= 0.6 mm, tool normals within
// 3 deg, no jump above 0.2 mm); the same panels without a dent must be trusted (a refused right answer is a failure
// too). Release build only (CI's sanitizer stage skips *Matrix*). SICP_DENT_SWEEP=1 runs every depth x width x noise
// x seed on the three (324 dented paths, the docs' table) and 150 undented paths instead of the covering subsets
// below. The known limit, a 0.5 mm deep dent under 0.15 mm noise (its expected significance near the check's 5
// standard errors at 0.45-0.75 scan points per mm^2 on the face; docs/sicp.md), is counted: trusted beyond the bar
// on at most as many paths as measured (seeds 31-33: one on each opening, in the subsets and in the sweep).

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "conform/datasets/panel.h"
#include "sicp_test_panels.h"

namespace conform {
namespace {

using test::beyond_bar;
using test::meets_bar_or_refused;
using test::new_panel;
using test::PanelRun;
using test::run;

constexpr double kNoise[] = {0.03, 0.06, 0.10, 0.15};
constexpr double kDepth[] = {0.5, 1.0, 1.5};
constexpr double kWidth[] = {10.0, 20.0, 30.0};
constexpr std::uint64_t kSeeds[] = {31, 32, 33};
constexpr double kDentAt[] = {0.3, 0.55, 0.8};  // per seed: where on the oval (share of a turn from +x)

// SICP_DENT_FIRST_SEED=N runs the matrix on another stream: dents on seeds N to N + 2 (at the same places), undented
// panels on N to N + 9 (with SICP_DENT_SWEEP=1). The counts at the limit are asserted on the default stream only.
std::uint64_t first_seed() {
  const char* text = std::getenv("SICP_DENT_FIRST_SEED");
  return text != nullptr ? std::strtoull(text, nullptr, 10) : kSeeds[0];
}
std::uint64_t seed_of(int s) { return first_seed() + static_cast<std::uint64_t>(s); }
bool default_stream() { return first_seed() == kSeeds[0]; }

std::string label(const PanelOptions& o, double depth, double width, double noise, std::uint64_t seed) {
  char text[96];
  std::snprintf(text, sizeof text, "%s, dent %.1f x %.0f mm, noise %.2f, seed %llu",
                o.shape == PanelShape::kNoseCone ? "nose cone" : to_string(o.opening), depth, width, noise,
                static_cast<unsigned long long>(seed));
  return text;
}

// The panel a matrix runs: the new plate with its oval or cut-out, or the reduced nose cone (50,000 scan points,
// a 2.4 m trapezoidal window with 3 mm corners on a 1 m barrel).
PanelOptions panel(PanelShape shape, PlateOpening opening, std::uint64_t seed) {
  if (shape == PanelShape::kPlate) return new_panel(opening, seed);
  PanelOptions o = test::reduced(PanelShape::kNoseCone);
  o.seed = seed;
  return o;
}

// Every depth and every noise level on every seed, the width cycling so that each depth meets each width at every
// noise level over the seeds, and the narrowest, shallowest dent (0.5 x 10 mm, the hardest to see) at every noise
// level on every seed (44 paths on the oval); the cut-out (the dent on its sides, away from the corners): every depth
// at the lowest and the highest noise on every seed, the width cycling, and 0.5 x 10 mm there too (24 paths).
// SICP_DENT_SWEEP=1: every width at every noise level on both openings (216 paths).
void dent_matrix(PanelShape shape, PlateOpening opening, int max_at_limit, int max_at_limit_swept) {
  const bool sweep = std::getenv("SICP_DENT_SWEEP") != nullptr;
  const bool oval = shape == PanelShape::kPlate && opening == PlateOpening::kEllipse;
  int dents = 0, refused = 0, at_limit = 0;
  for (int s = 0; s < 3; ++s) {
    for (int n = 0; n < 4; ++n) {
      if (!sweep && !oval && n != 0 && n != 3) continue;
      for (int d = 0; d < 3; ++d) {
        for (int w = 0; w < 3; ++w) {
          if (!sweep && w != (s + n + d) % 3 && !(d == 0 && w == 0)) continue;
          PanelOptions o = panel(shape, opening, seed_of(s));
          o.noise_mm = kNoise[n];
          o.dent_depth_mm = kDepth[d];
          o.dent_width_mm = kWidth[w];
          o.dent_at = kDentAt[s];
          const PanelRun r = run(o);
          const std::string what = label(o, kDepth[d], kWidth[w], kNoise[n], seed_of(s));
          ++dents;
          // The documented limit (docs/sicp.md): a 0.5 mm deep dent at 0.15 mm noise may be trusted beyond the bar
          // (its expected significance is near the check's 5 standard errors); counted, not more than measured.
          if (r.result.trusted && beyond_bar(r.error) && kDepth[d] == 0.5 && kNoise[n] == 0.15) {
            std::printf("%-44s trusted beyond the bar (the documented limit): off path %.3f / %.3f mm, normals "
                        "%.2f deg\n", what.c_str(), r.error.path_mean_mm, r.error.path_max_mm, r.error.normal_max_deg);
            ++at_limit;
            continue;
          }
          if (!meets_bar_or_refused(r, what)) {
            ++refused;
            EXPECT_NE(r.result.check.reason.find("departs from the model"), std::string::npos) << what;
          }
        }
      }
    }
  }
  std::printf("%d of %d dented paths refused, %d trusted beyond the bar at the limit\n", refused, dents, at_limit);
  if (default_stream()) {
    EXPECT_LE(at_limit, sweep ? max_at_limit_swept : max_at_limit);
  }
}

TEST(SicpDentMatrix, DentsAreCaughtAtEveryNoiseLevel) { dent_matrix(PanelShape::kPlate, PlateOpening::kEllipse, 1, 1); }

TEST(SicpDentMatrix, DentsOnTheCutOutAreCaught) {
  dent_matrix(PanelShape::kPlate, PlateOpening::kRoundedRectangle, 1, 1);
}

// The nose cone (its window's sides, away from the corners): as the cut-out, every depth at the lowest and the
// highest noise, the width cycling, and 0.5 x 10 mm (24 paths); SICP_DENT_SWEEP=1: 108.
TEST(SicpDentMatrix, DentsOnTheNoseConeAreCaught) {
  dent_matrix(PanelShape::kNoseCone, PlateOpening::kEllipse, 1, 1);
}

// The same panels without a dent: trusted at every noise level and seed, oval and cut-out. SICP_DENT_SWEEP=1: seeds
// 31-40, noise 0.02-0.15 mm, both openings.
TEST(SicpDentMatrix, UndentedPathsStayTrusted) {
  const bool sweep = std::getenv("SICP_DENT_SWEEP") != nullptr;
  for (const PlateOpening opening : {PlateOpening::kEllipse, PlateOpening::kRoundedRectangle}) {
    for (std::uint64_t seed = first_seed(); seed <= first_seed() + (sweep ? 9u : 2u); ++seed) {
      for (const double noise : {0.02, 0.03, 0.06, 0.10, 0.15}) {
        if (!sweep && (noise == 0.02 || (opening == PlateOpening::kRoundedRectangle && noise != 0.03 && noise != 0.15)))
          continue;
        PanelOptions o = new_panel(opening, seed);
        o.noise_mm = noise;
        const PanelRun r = run(o);
        char what[96];
        std::snprintf(what, sizeof what, "no dent, %s, noise %.2f, seed %llu", to_string(opening), noise,
                      static_cast<unsigned long long>(seed));
        EXPECT_TRUE(meets_bar_or_refused(r, what)) << what << ": " << r.result.check.reason;
        EXPECT_EQ(r.result.check.misfit_rows, 0u) << what;
      }
    }
  }
}

// The reduced nose cone without a dent: trusted at the lowest and the highest noise, seeds 31-33; SICP_DENT_SWEEP=1:
// seeds 31-40, noise 0.02-0.15 mm.
TEST(SicpDentMatrix, UndentedNoseConesStayTrusted) {
  const bool sweep = std::getenv("SICP_DENT_SWEEP") != nullptr;
  for (std::uint64_t seed = first_seed(); seed <= first_seed() + (sweep ? 9u : 2u); ++seed) {
    for (const double noise : {0.02, 0.03, 0.06, 0.10, 0.15}) {
      if (!sweep && noise != 0.03 && noise != 0.15) continue;
      PanelOptions o = panel(PanelShape::kNoseCone, PlateOpening::kEllipse, seed);
      o.noise_mm = noise;
      const PanelRun r = run(o);
      char what[96];
      std::snprintf(what, sizeof what, "no dent, nose cone, noise %.2f, seed %llu", noise,
                    static_cast<unsigned long long>(seed));
      EXPECT_TRUE(meets_bar_or_refused(r, what)) << what << ": " << r.result.check.reason;
      EXPECT_EQ(r.result.check.misfit_rows, 0u) << what;
    }
  }
}

// Laser-stripe scans: the oval, the cut-out and the nose cone at 0.15 mm noise, seeds 31-33, undented and with a
// 1.0 x 20 mm dent, the stripes spacing_mm apart on planes turned angle_deg about z from across x. No path may be
// trusted beyond the bar. Returns the undented paths trusted; prints each opening's counts.
int stripe_matrix(double spacing_mm, double angle_deg) {
  int undented_trusted = 0;
  for (const PanelShape shape : {PanelShape::kPlate, PanelShape::kNoseCone}) {
    for (const PlateOpening opening : {PlateOpening::kEllipse, PlateOpening::kRoundedRectangle}) {
      if (shape == PanelShape::kNoseCone && opening == PlateOpening::kRoundedRectangle) continue;
      int trusted[2] = {0, 0};
      for (int s = 0; s < 3; ++s) {
        for (const double depth : {0.0, 1.0}) {
          PanelOptions o = panel(shape, opening, seed_of(s));
          o.noise_mm = 0.15;
          o.stripe_spacing_mm = spacing_mm;
          o.stripe_angle_deg = angle_deg;
          o.dent_depth_mm = depth;
          o.dent_width_mm = 20.0;
          o.dent_at = kDentAt[s];
          const PanelRun r = run(o);
          char prefix[64];
          std::snprintf(prefix, sizeof prefix, "stripes %.0f mm at %.0f deg, ", spacing_mm, angle_deg);
          if (meets_bar_or_refused(r, prefix + label(o, depth, 20.0, 0.15, seed_of(s)))) ++trusted[depth > 0.0 ? 1 : 0];
        }
      }
      undented_trusted += trusted[0];
      std::printf("stripes %.0f mm at %.0f deg, %s: undented trusted %d of 3, dented 1.0 x 20 mm trusted %d of 3\n",
                  spacing_mm, angle_deg, shape == PanelShape::kNoseCone ? "nose cone" : to_string(opening),
                  trusted[0], trusted[1]);
    }
  }
  return undented_trusted;
}

// Stripes along an edge without its flank (across x: the cut-out's and the nose cone's sides across x, two arcs of
// the oval) leave where the edge lies across unmeasured there: those rows are refused (paths 0.65-4 mm off at peak
// were trusted before the rule, and no stretch length separated them from paths within the bar: the ovals, 0.19-0.34
// mm, are refused too). 2 mm stripes at 45 deg cross every edge but where the oval runs along them: the cut-out and
// the nose cone are trusted (measured: 6 of 6 undented). SICP_DENT_SWEEP=1: also 1 and 3 mm, across x, at 45 and at
// 90 deg (the counts in docs/measurements/sicp.md).
TEST(SicpDentMatrix, StripeScansAreTrustedOnlyWithinTheBar) {
  stripe_matrix(2.0, 0.0);
  const int across = stripe_matrix(2.0, 45.0);
  if (default_stream()) {
    EXPECT_EQ(across, 6);
  }
  if (std::getenv("SICP_DENT_SWEEP") == nullptr) return;
  for (const double spacing : {1.0, 2.0, 3.0}) {
    for (const double angle : {0.0, 45.0, 90.0}) {
      if (spacing != 2.0 || (angle != 0.0 && angle != 45.0)) stripe_matrix(spacing, angle);
    }
  }
}

// A dent between sparse stripes: 3 mm stripes at 45 deg on the nose cone leave rows whose 6 mm disc holds one stripe,
// a line that fixes no plane. Those rows were left unchecked and, on seed 41, the path was trusted 0.87 mm off at
// peak (tool normals 7.0 deg off) over a 1.0 x 20 mm dent; the plane is now fitted within twice the disc there.
// Seeds 41-43 (the held-out stream where it was found): none trusted beyond the bar.
TEST(SicpDentMatrix, ADentBetweenSparseStripesIsNotTrusted) {
  for (const std::uint64_t seed : {41u, 42u, 43u}) {
    PanelOptions o = panel(PanelShape::kNoseCone, PlateOpening::kEllipse, seed);
    o.noise_mm = 0.15;
    o.stripe_spacing_mm = 3.0;
    o.stripe_angle_deg = 45.0;
    o.dent_depth_mm = 1.0;
    o.dent_width_mm = 20.0;
    o.dent_at = kDentAt[0];
    const PanelRun r = run(o);
    meets_bar_or_refused(r, "stripes 3 mm at 45 deg, " + label(o, 1.0, 20.0, 0.15, seed));
  }
}

// A side the stripes run along (the cut-out's sides across x under stripes across x) has no flank and no face's end
// scanned: the last stripe lies up to a stripe spacing inside the edge, and nothing holds the rows there across.
// Those rows must be reported unanchored and the path refused, whatever else the checks find (measured at 2 mm
// stripes, seeds 31-33: 78-137 rows, paths 0.70-0.88 mm off at peak; a first try at holding rows by where the
// stripes end took gaps in the last stripe for ends and held all but 1-31 of them).
TEST(SicpDentMatrix, StripesAlongASideLeaveItUnanchored) {
  for (const std::uint64_t seed : kSeeds) {
    PanelOptions o = new_panel(PlateOpening::kRoundedRectangle, seed);
    o.noise_mm = 0.15;
    o.stripe_spacing_mm = 2.0;
    const PanelRun r = run(o);
    char what[96];
    std::snprintf(what, sizeof what, "stripes 2 mm along the cut-out's sides, seed %llu",
                  static_cast<unsigned long long>(seed));
    meets_bar_or_refused(r, what);
    EXPECT_FALSE(r.result.trusted) << what;
    EXPECT_GE(r.result.check.unanchored_rows, 60u) << what;
  }
}

}  // namespace
}  // namespace conform
