#pragma once
// The groove (cutting) angle around the joint, Lind & Ystgaard (2020), Eq. (5), generalised: any list of
// (phi_i, alpha_i) rows, phi the stub azimuth from the toe, interpolated with cyclic boundary conditions. The paper's
// convention (phi_0 = 0 at the toe; a last row at 2 pi repeats the first's alpha) is accepted and checked; a table
// without the 2 pi row is closed cyclically. The quarters (toe, side, heel, side) are the table
// {(0, a0), (pi/2, a1), (pi, a2), (3 pi/2, a3)}.
//
//   linear     alpha_i + (alpha_{i+1} - alpha_i) u, u the fraction of the span
//   quadratic  C1 and flat at the rows: u replaced by q(u) = 2u^2 (u < 1/2), 1 - 2(1 - u)^2 (u >= 1/2)
//   spline     the periodic cubic spline through the rows (C2 across 2 pi); it may overshoot between rows, which
//              groove_table IsValid checks on a fine grid.

#include <string>
#include <utility>
#include <vector>

namespace conform {

enum class GrooveInterpolation { kLinear, kQuadratic, kSpline };

class GrooveTable {
 public:
  GrooveTable() = default;
  // Rows (phi_rad, alpha_rad). Not checked here: call IsValid.
  GrooveTable(std::vector<std::pair<double, double>> rows, GrooveInterpolation interpolation);
  static GrooveTable quarters(double toe, double side1, double heel, double side2, GrooveInterpolation interpolation);

  // Every phi in [0, 2 pi], strictly increasing; a 2 pi row only after a row at 0 and with its alpha; >= 1 row
  // (>= 3 distinct for the spline); every alpha, and the interpolated alpha on a 0.1 deg grid, in [0, pi/2).
  bool IsValid(std::string* error) const;

  // alpha at phi (any value, wrapped into [0, 2 pi)), rad.
  double at(double phi_rad) const;

  const std::vector<std::pair<double, double>>& rows() const { return rows_; }
  GrooveInterpolation interpolation() const { return interpolation_; }

 private:
  void prepare();
  std::vector<std::pair<double, double>> rows_;  // as given
  GrooveInterpolation interpolation_ = GrooveInterpolation::kLinear;
  std::vector<double> phi_;  // the cyclic nodes in [0, 2 pi) (a 2 pi row dropped)
  std::vector<double> alpha_;
  std::vector<double> second_;  // the spline's second derivatives at the nodes
};

}  // namespace conform
