#pragma once
// An ordered sequence of points in millimetres, open or closed (the last point joins the first).

#include <vector>

#include <Eigen/Core>

namespace conform {

struct Polyline {
  std::vector<Eigen::Vector3d> points;  // mm
  bool closed = false;
};

// Sum of segment lengths, including the closing segment of a closed polyline (mm).
double length(const Polyline& polyline);

}  // namespace conform
