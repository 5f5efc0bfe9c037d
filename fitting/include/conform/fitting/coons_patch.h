#pragma once
// A bilinearly blended Coons patch (Farin, Curves and Surfaces for CAGD, 22.2): the surface spanned by four boundary
// curves that meet at the corners,
//   r(u, v) = (1-v) c0(u) + v c1(u) + (1-u) d0(v) + u d1(v) - [bilinear interpolant of the four corners],
// u, v in [0, 1]. It reproduces its four boundary curves exactly: the way to rebuild a reference surface over a
// damaged area from the undamaged measurement around it.

#include <functional>

#include <Eigen/Core>

#include "conform/fitting/surface_grid.h"

namespace conform {

using BoundaryCurve = std::function<Eigen::Vector3d(double)>;  // t in [0, 1] -> point, mm

class CoonsPatch {
 public:
  // c0(u) = r(u, 0), c1(u) = r(u, 1), d0(v) = r(0, v), d1(v) = r(1, v). Throws conform::Error when a curve is
  // empty or the corners do not meet within `corner_tolerance_mm`.
  CoonsPatch(BoundaryCurve c0, BoundaryCurve c1, BoundaryCurve d0, BoundaryCurve d1, double corner_tolerance_mm = 1e-6);

  Eigen::Vector3d position(double u, double v) const;
  // The patch sampled on rows x cols points at equal parameter steps (u along the columns, v along the rows).
  SurfaceGrid sample(int rows, int cols) const;

 private:
  BoundaryCurve c0_, c1_, d0_, d1_;
};

// The Coons patch of a grid's border (its first and last rows and columns, as piecewise-linear curves): the grid's
// interior rebuilt from its edges alone.
CoonsPatch coons_patch_of_border(const SurfaceGrid& grid);

}  // namespace conform
