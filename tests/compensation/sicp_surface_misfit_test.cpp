// The surface misfit (sicp_surface_misfit.h) and its check (check_sicp_path): a flat scanned face beside a straight
// 200 mm path, one point per mm^2, the model the plane z = 0. A dent at the edge is found whatever the noise, in the
// rows over it; a flat scan and stray points are not.

#include "conform/compensation/sicp_surface_misfit.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "conform/compensation/sicp_checks.h"
#include "conform/core/error.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/random.h"

namespace conform {
namespace {

struct Face {
  Polyline contour;
  Trajectory path;
  std::vector<Eigen::Vector3d> scan;
};

// The path along x at y = 0 (rows 1 mm apart), the face on y in [0, 30] mm and its flank on y = 0, z in [-4, -1.5]
// (none for x in [no_flank_from, no_flank_to]); a Gaussian dent of `depth` (full width 4 sigma) centred on the edge at
// x = 100; a share of stray points 5-20 mm off.
Face make_face(double noise_mm, double depth_mm, double width_mm, double stray_share, std::uint64_t seed,
               double no_flank_from = 0.0, double no_flank_to = 0.0) {
  Face f;
  for (int i = 0; i <= 200; ++i) {
    f.contour.points.emplace_back(i, 0.0, 0.0);
    f.path.points.emplace_back(i, 0.0, 0.0);
    f.path.normals.emplace_back(0.0, 0.0, 1.0);
  }
  Random place(seed, 0), noise(seed, 1), stray(seed, 2);
  const double sigma = 0.25 * width_mm;
  for (int k = 0; k < 220 * 30; ++k) {
    const double x = place.uniform(-10.0, 210.0), y = place.uniform(0.0, 30.0);
    double z =
        noise_mm * noise.normal() - depth_mm * std::exp(-((x - 100.0) * (x - 100.0) + y * y) / (2 * sigma * sigma));
    if (stray.uniform() < stray_share) z += (stray.uniform() < 0.5 ? -1.0 : 1.0) * stray.uniform(5.0, 20.0);
    f.scan.emplace_back(x, y, z);
  }
  for (int k = 0; k < 220 * 3; ++k) {  // the flank, 2.5 mm tall, at the face's density
    const double x = place.uniform(-10.0, 210.0), z = place.uniform(-4.0, -1.5);
    if (x < no_flank_from || x > no_flank_to) f.scan.emplace_back(x, noise_mm * noise.normal(), z);
  }
  return f;
}

// The plane z = 0 and, below 1.2 mm next to the edge, the flank y = 0 facing the opening.
bool flat_model(const Eigen::Vector3d& q, std::size_t, double& residual, Eigen::Vector3d& normal) {
  const bool flank = q.z() < -1.2 && q.y() < 1.0;
  residual = flank ? -q.y() : q.z();
  normal = flank ? Eigen::Vector3d(-Eigen::Vector3d::UnitY()) : Eigen::Vector3d(Eigen::Vector3d::UnitZ());
  return true;
}

SicpCheck judge(const Face& f, double noise_mm, std::vector<SicpRowMisfit>* misfit = nullptr) {
  const KdTree tree(f.scan);
  const std::vector<SicpRowMisfit> m =
      sicp_surface_misfit(f.path, f.path.normals, f.scan, tree, noise_mm, flat_model, SicpMisfitOptions{});
  if (misfit != nullptr) *misfit = m;
  SicpResult registration;
  registration.converged = true;
  return check_sicp_path(f.contour, registration, f.path, f.path, SicpCheckOptions{}, noise_mm, {}, m);
}

TEST(SicpSurfaceMisfit, FlatScanIsTrustedAtEveryNoiseLevel) {
  for (const double noise : {0.02, 0.05, 0.1, 0.15}) {
    for (const std::uint64_t seed : {1, 2, 3}) {
      std::vector<SicpRowMisfit> m;
      const SicpCheck c = judge(make_face(noise, 0.0, 20.0, 0.0, seed), noise, &m);
      EXPECT_TRUE(c.trusted) << "noise " << noise << ", seed " << seed << ": " << c.reason;
      EXPECT_EQ(c.misfit_rows, 0u);
      EXPECT_GT(m[100].points, 20u);
      EXPECT_LT(std::abs(m[100].offset_mm), 5.0 * m[100].offset_se_mm + 1e-9);
    }
  }
}

// A dent 0.5-1 mm deep, 10-20 mm wide, at the edge: refused at 0.03 and 0.15 mm noise alike, the stretch over the
// dent named, no row far from it flagged. Its offset and slope are measured where they are.
TEST(SicpSurfaceMisfit, DentIsFoundWhateverTheNoise) {
  for (const double noise : {0.03, 0.15}) {
    for (const double depth : {0.5, 1.0}) {
      for (const double width : {10.0, 20.0}) {
        std::vector<SicpRowMisfit> m;
        const SicpCheck c = judge(make_face(noise, depth, width, 0.0, 7), noise, &m);
        const std::string what =
            std::to_string(depth) + " x " + std::to_string(width) + " mm, noise " + std::to_string(noise);
        EXPECT_FALSE(c.trusted) << what;
        EXPECT_GT(c.misfit_rows, 0u) << what;
        for (std::size_t i = 0; i < c.rows.size(); ++i) {
          if (c.rows[i].misfit) {
            EXPECT_LE(std::abs(static_cast<double>(i) - 100.0), width) << what << ", row " << i;
          }
        }
        EXPECT_LT(m[100].offset_mm, -0.25 * depth) << what;
        EXPECT_NE(c.reason.find("departs from the model"), std::string::npos) << c.reason;
        ASSERT_FALSE(c.warnings.empty());
        EXPECT_NE(c.warnings.back().find("rows "), std::string::npos) << c.warnings.back();
      }
    }
  }
}

// The narrow dent's matched filter: a Gaussian bump over a quadratic background within 18 mm measures the dent's depth
// and the slope it implies at its steepest (depth e^-1/2 / sigma: 6.9 deg for 0.5 x 10 mm) at the row over it, in
// spite of a smooth misfit of the model (a tilt and a curvature of the residuals, which a plane in 6 mm would take
// for part of the dent); at 0.15 mm noise on one point per mm^2 it is significant (here about 8 standard errors).
TEST(SicpSurfaceMisfit, NarrowDentDepthAndSlopeAreMeasured) {
  for (const std::uint64_t seed : {7, 8, 9}) {
    Face f = make_face(0.15, 0.5, 10.0, 0.0, seed, -20.0, 220.0);  // the face only: the model below has no flank
    for (Eigen::Vector3d& q : f.scan) q.z() += 0.002 * (q.x() - 100.0) + 1e-4 * (q.x() - 100.0) * (q.x() - 100.0);
    const auto background = [](const Eigen::Vector3d& q, std::size_t, double& residual, Eigen::Vector3d& normal) {
      residual = q.z();
      normal = Eigen::Vector3d::UnitZ();
      return true;
    };
    const KdTree tree(f.scan);
    const std::vector<SicpRowMisfit> m =
        sicp_surface_misfit(f.path, f.path.normals, f.scan, tree, 0.15, background, SicpMisfitOptions{});
    EXPECT_NEAR(m[100].dent_mm, -0.5, 0.12) << seed;
    EXPECT_NEAR(m[100].dent_slope_deg, std::atan(0.5 * std::exp(-0.5) / 2.5) * 180.0 / M_PI, 1.7) << seed;
    EXPECT_GT(m[100].dent_z, 5.0) << seed;
    EXPECT_LT(m[40].dent_z, 5.0) << seed;  // 60 mm away: the background only
    EXPECT_LT(m[160].dent_z, 5.0) << seed;
  }
}

TEST(SicpSurfaceMisfit, StrayPointsAreLeftOut) {
  for (const double share : {0.001, 0.01}) {
    const SicpCheck c = judge(make_face(0.05, 0.0, 20.0, share, 4), 0.05);
    EXPECT_TRUE(c.trusted) << share << ": " << c.reason;
  }
}

// Where neither the flank nor the face's own end is scanned, nothing measures the edge across: a stretch of such rows
// longer than a short bridge is not trusted (named in the reason), a short one is bridged; the flank's points are
// counted per row (about 2.5 mm x 12 mm at one point per mm^2 within the 6 mm disc).
TEST(SicpSurfaceMisfit, EdgeWithoutFlankOrFaceEndIsNotTrusted) {
  std::vector<SicpRowMisfit> m;
  const SicpCheck held = judge(make_face(0.05, 0.0, 20.0, 0.0, 5), 0.05, &m);
  EXPECT_TRUE(held.trusted) << held.reason;
  EXPECT_GT(m[100].flank_points, 15u);
  EXPECT_EQ(held.unanchored_rows, 0u);
  const SicpCheck bare = judge(make_face(0.05, 0.0, 20.0, 0.0, 5, -20.0, 220.0), 0.05, &m);
  EXPECT_FALSE(bare.trusted);
  EXPECT_EQ(m[100].flank_points, 0u);
  EXPECT_EQ(bare.unanchored_rows, bare.rows.size());
  EXPECT_NE(bare.reason.find("without scan of the flank"), std::string::npos) << bare.reason;
  const SicpCheck gap = judge(make_face(0.05, 0.0, 20.0, 0.0, 5, 80.0, 130.0), 0.05, &m);
  EXPECT_FALSE(gap.trusted);
  EXPECT_GT(gap.unanchored_rows, 30u);
  EXPECT_LT(gap.unanchored_rows, 50u);
  EXPECT_FALSE(gap.rows[60].unanchored);
  EXPECT_TRUE(gap.rows[105].unanchored);
  const SicpCheck bridged = judge(make_face(0.05, 0.0, 20.0, 0.0, 5, 95.0, 105.0), 0.05, &m);
  EXPECT_TRUE(bridged.trusted) << bridged.reason;
}

TEST(SicpSurfaceMisfit, InvalidOptionsAndSizesAreRefused) {
  const Face f = make_face(0.05, 0.0, 20.0, 0.0, 1);
  const KdTree tree(f.scan);
  SicpMisfitOptions o;
  o.near_radius_mm = 8.0;  // beyond the plane's radius
  EXPECT_THROW(sicp_surface_misfit(f.path, f.path.normals, f.scan, tree, 0.05, flat_model, o), Error);
  o = SicpMisfitOptions{};
  o.neighbour_to_mm = 4.0;
  EXPECT_THROW(sicp_surface_misfit(f.path, f.path.normals, f.scan, tree, 0.05, flat_model, o), Error);
  o = SicpMisfitOptions{};
  o.dent_radius_mm = 4.0;  // under twice the bump's sigma
  EXPECT_THROW(sicp_surface_misfit(f.path, f.path.normals, f.scan, tree, 0.05, flat_model, o), Error);
  o = SicpMisfitOptions{};
  o.dent_sigma_mm = 0.0;
  EXPECT_THROW(sicp_surface_misfit(f.path, f.path.normals, f.scan, tree, 0.05, flat_model, o), Error);
  const std::vector<Eigen::Vector3d> too_few(3, Eigen::Vector3d::UnitZ());
  EXPECT_THROW(sicp_surface_misfit(f.path, too_few, f.scan, tree, 0.05, flat_model, SicpMisfitOptions{}), Error);
  SicpCheckOptions c;
  c.max_normal_error_deg = 0.0;
  std::string why;
  EXPECT_FALSE(c.IsValid(&why));
  EXPECT_NE(why.find("normal"), std::string::npos);
  c = SicpCheckOptions{};
  c.max_dent_slope_deg = -1.0;
  EXPECT_FALSE(c.IsValid(&why));
  EXPECT_NE(why.find("dent"), std::string::npos);
}

}  // namespace
}  // namespace conform
