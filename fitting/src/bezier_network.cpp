#include "conform/fitting/bezier_network.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Dense>

#include "conform/core/error.h"

namespace conform {
namespace {

using Points = std::vector<Eigen::Vector3d>;

// b_ij of the patch from corner values, slopes and twists: a corner's inner neighbours move by a third of the
// slope along the edge, the inner point by both thirds and a ninth of the twist (the Hermite-to-Bézier map).
BezierPatch hermite_patch(const Eigen::Vector3d q[2][2], const Eigen::Vector3d du[2][2], const Eigen::Vector3d dv[2][2],
                          const Eigen::Vector3d duv[2][2]) {
  BezierPatch patch;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const int a = i < 2 ? 0 : 1, b = j < 2 ? 0 : 1;
      const double su = (i == 1) ? 1.0 : (i == 2 ? -1.0 : 0.0);
      const double sv = (j == 1) ? 1.0 : (j == 2 ? -1.0 : 0.0);
      patch.control(i, j) = q[a][b] + su * du[a][b] / 3.0 + sv * dv[a][b] / 3.0 + su * sv * duv[a][b] / 9.0;
    }
  }
  return patch;
}

}  // namespace

Points natural_spline_slopes(const Points& values) {
  const std::size_t n = values.size();
  Points d(n, Eigen::Vector3d::Zero());
  if (n < 2) return d;
  // Thomas algorithm on the tridiagonal system (diagonally dominant: no pivoting needed).
  std::vector<double> diag(n, 4.0), upper(n, 1.0);
  Points rhs(n);
  diag[0] = 2.0;
  diag[n - 1] = 2.0;
  rhs[0] = 3.0 * (values[1] - values[0]);
  rhs[n - 1] = 3.0 * (values[n - 1] - values[n - 2]);
  for (std::size_t k = 1; k + 1 < n; ++k) rhs[k] = 3.0 * (values[k + 1] - values[k - 1]);
  for (std::size_t k = 1; k < n; ++k) {
    const double m = 1.0 / diag[k - 1];  // lower[k] = 1
    diag[k] -= m * upper[k - 1];
    rhs[k] -= m * rhs[k - 1];
  }
  d[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t k = n - 1; k-- > 0;) d[k] = (rhs[k] - upper[k] * d[k + 1]) / diag[k];
  return d;
}

BezierNetwork::BezierNetwork(const SurfaceGrid& grid) {
  if (grid.rows < 2 || grid.cols < 2) throw Error("Bézier network: the grid needs at least 2 x 2 points");
  const std::size_t rows = static_cast<std::size_t>(grid.rows), cols = static_cast<std::size_t>(grid.cols);
  if (grid.points.size() != rows * cols) throw Error("Bézier network: grid point count does not match rows x cols");
  for (const Eigen::Vector3d& p : grid.points) {
    if (!p.allFinite()) throw Error("Bézier network: a grid point is not finite");
  }
  Points du(rows * cols), dv(rows * cols), duv(rows * cols);
  for (std::size_t r = 0; r < rows; ++r) {  // along u (a row)
    const Points row(grid.points.begin() + static_cast<long>(r * cols),
                     grid.points.begin() + static_cast<long>((r + 1) * cols));
    const Points slopes = natural_spline_slopes(row);
    std::copy(slopes.begin(), slopes.end(), du.begin() + static_cast<long>(r * cols));
  }
  for (std::size_t c = 0; c < cols; ++c) {  // along v (a column), of the points and of their u-slopes
    Points column(rows), column_du(rows);
    for (std::size_t r = 0; r < rows; ++r) column[r] = grid.points[r * cols + c], column_du[r] = du[r * cols + c];
    const Points slopes = natural_spline_slopes(column), twists = natural_spline_slopes(column_du);
    for (std::size_t r = 0; r < rows; ++r) dv[r * cols + c] = slopes[r], duv[r * cols + c] = twists[r];
  }
  patch_rows_ = grid.rows - 1;
  patch_cols_ = grid.cols - 1;
  patches_.reserve(static_cast<std::size_t>(patch_rows_ * patch_cols_));
  for (std::size_t r = 0; r + 1 < rows; ++r) {
    for (std::size_t c = 0; c + 1 < cols; ++c) {
      Eigen::Vector3d q[2][2], pu[2][2], pv[2][2], puv[2][2];
      for (std::size_t a = 0; a < 2; ++a) {    // a: along u (column)
        for (std::size_t b = 0; b < 2; ++b) {  // b: along v (row)
          const std::size_t k = (r + b) * cols + (c + a);
          q[a][b] = grid.points[k], pu[a][b] = du[k], pv[a][b] = dv[k], puv[a][b] = duv[k];
        }
      }
      patches_.push_back(hermite_patch(q, pu, pv, puv));
    }
  }
}

BezierNetwork::BezierNetwork(int patch_rows, int patch_cols, std::vector<BezierPatch> patches)
    : patch_rows_(patch_rows), patch_cols_(patch_cols), patches_(std::move(patches)) {
  if (patch_rows < 1 || patch_cols < 1 || patches_.size() != static_cast<std::size_t>(patch_rows * patch_cols)) {
    throw Error("Bézier network: expected " + std::to_string(patch_rows) + " x " + std::to_string(patch_cols) +
                " patches, got " + std::to_string(patches_.size()));
  }
}

ParameterDomain BezierNetwork::domain() const {
  return {0.0, static_cast<double>(patch_cols_), 0.0, static_cast<double>(patch_rows_)};
}

Eigen::Vector3d BezierNetwork::derivative(double u, double v, int du, int dv) const {
  const int c = std::clamp(static_cast<int>(std::floor(u)), 0, patch_cols_ - 1);
  const int r = std::clamp(static_cast<int>(std::floor(v)), 0, patch_rows_ - 1);
  return patch(r, c).derivative(u - c, v - r, du, dv);
}

}  // namespace conform
