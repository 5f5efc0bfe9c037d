#pragma once
// A network of bicubic Bézier patches interpolating a rectangular grid of points (surface_grid.h) with C2 continuity:
// the tensor-product natural cubic spline through the grid (uniform parameters: u runs along the columns, 0 at column
// 0 to cols - 1 at the last, v along the rows likewise), converted patch by patch to Bézier form from its values,
// first derivatives and twist at the grid points (Farin, Curves and Surfaces for CAGD, 17.5). Patch (r, c) covers
// u in [c, c + 1], v in [r, r + 1] and passes through the four grid points at its corners exactly.

#include <vector>

#include <Eigen/Core>

#include "conform/fitting/bezier_patch.h"
#include "conform/fitting/parametric_surface.h"
#include "conform/fitting/surface_grid.h"

namespace conform {

class BezierNetwork : public ParametricSurface {
 public:
  BezierNetwork() = default;
  // Throws conform::Error when the grid is smaller than 2 x 2, its point count does not match, or a point is not
  // finite.
  explicit BezierNetwork(const SurfaceGrid& grid);
  // A network from given patches, row-major (patches[r * patch_cols + c]); neighbours should meet along their edges.
  // Throws conform::Error when the count does not match.
  BezierNetwork(int patch_rows, int patch_cols, std::vector<BezierPatch> patches);

  int patch_rows() const { return patch_rows_; }
  int patch_cols() const { return patch_cols_; }
  const BezierPatch& patch(int r, int c) const { return patches_[static_cast<std::size_t>(r * patch_cols_ + c)]; }

  // u in [0, cols - 1], v in [0, rows - 1].
  ParameterDomain domain() const override;
  // Outside the domain the edge patches extrapolate (useful for Newton steps that overshoot).
  Eigen::Vector3d derivative(double u, double v, int du, int dv) const override;

 private:
  int patch_rows_ = 0;
  int patch_cols_ = 0;
  std::vector<BezierPatch> patches_;
};

// The first derivatives at the knots 0, 1, ..., n - 1 of the natural cubic spline through `values` (unit spacing):
// the tridiagonal system D[k-1] + 4 D[k] + D[k+1] = 3 (Q[k+1] - Q[k-1]), with zero second derivative at both ends.
std::vector<Eigen::Vector3d> natural_spline_slopes(const std::vector<Eigen::Vector3d>& values);

}  // namespace conform
