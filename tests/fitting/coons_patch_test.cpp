// The bilinearly blended Coons patch: reproduces its boundary curves and a plane; rebuilt from a grid's border.

#include <cmath>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "conform/core/error.h"
#include "conform/fitting/coons_patch.h"
#include "conform/fitting/surface_grid.h"

namespace conform {
namespace {

TEST(CoonsPatch, ReproducesItsBoundaryAndAPlane) {
  const auto plane = [](double u, double v) { return Eigen::Vector3d(40 * u, 30 * v, 2 + 0.5 * u - 0.2 * v); };
  const CoonsPatch coons([&](double t) { return plane(t, 0); }, [&](double t) { return plane(t, 1); },
                         [&](double t) { return plane(0, t); }, [&](double t) { return plane(1, t); });
  for (double u = 0.0; u <= 1.0; u += 0.125) {
    for (double v = 0.0; v <= 1.0; v += 0.125) EXPECT_LT((coons.position(u, v) - plane(u, v)).norm(), 1e-12);
  }
  // Curved boundaries: reproduced exactly on the edges.
  const CoonsPatch curved([](double t) { return Eigen::Vector3d(t, 0, std::sin(3 * t)); },
                          [](double t) { return Eigen::Vector3d(t, 1, std::sin(3 * t) + t * t); },
                          [](double t) { return Eigen::Vector3d(0, t, 0); },
                          [](double t) { return Eigen::Vector3d(1, t, std::sin(3.0) + t * t * t); });
  for (double t = 0.0; t <= 1.0; t += 0.1) {
    EXPECT_LT((curved.position(t, 0) - Eigen::Vector3d(t, 0, std::sin(3 * t))).norm(), 1e-12);
    EXPECT_LT((curved.position(1, t) - Eigen::Vector3d(1, t, std::sin(3.0) + t * t * t)).norm(), 1e-12);
  }
  EXPECT_THROW(CoonsPatch([](double t) { return Eigen::Vector3d(t, 0, 0); }, [](double t) { return Eigen::Vector3d(t, 1, 0); },
                          [](double t) { return Eigen::Vector3d(0, t, 1); }, [](double t) { return Eigen::Vector3d(1, t, 0); }),
               Error);
  const SurfaceGrid sampled = coons.sample(5, 7);
  const CoonsPatch rebuilt = coons_patch_of_border(sampled);
  EXPECT_LT((rebuilt.position(0.4, 0.6) - plane(0.4, 0.6)).norm(), 1e-12);
}

}  // namespace
}  // namespace conform
