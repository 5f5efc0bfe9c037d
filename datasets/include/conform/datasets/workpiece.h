#pragma once
// A machined workpiece as a laser profiler sees it from above: a block's top face with a shoulder (a step down along
// one long edge), a rectangular pocket, a round pocket (a bore) and a slot, laid out without symmetry, as a height
// field (no points on the vertical walls). Sampled at random over a window of x: the whole top is a golden-sample
// scan, a window of 30-80 % of the length a partial scan of the same part. The nearest generated equivalent of
// issue 13's real pair (a partial profiler scan of a machined part against its golden-sample scan, ~0.2 mm noise).
//
// Height, mm, over x in [-length/2, length/2], y in [-width/2, width/2] (s as in ribbed_plate.h: a smoothstep wall
// of horizontal run `ramp`, 1 inside the feature, 0 outside):
//   z = - shoulder_depth * s(y - y_s)                          (y_s = width/2 - shoulder_width; one-sided)
//       - pocket_depth   * s(x - x_p, a_p) * s(y - y_p, b_p)   (rectangular pocket, half sides a_p, b_p)
//       - bore_depth     * s(|(x, y) - c_b|, r_b)             (round pocket)
//       - slot_depth     * s(x - x_l, a_l) * s(y - y_l, b_l)   (slot)
// with the features' places and sizes fixed fractions of length and width (workpiece.cpp).

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct WorkpieceOptions {
  double length_mm = 160.0;  // along x
  double width_mm = 100.0;   // along y
  double ramp_mm = 0.8;      // horizontal run of every wall (steep, not vertical)
  // The sampled window of x, as shares of the length from the -x end: [x_from, x_to] within [0, 1].
  double x_from = 0.0;
  double x_to = 1.0;
  std::size_t points = 20000;  // uniform over the window
  double noise_mm = 0.2;       // Gaussian along z, sigma
  double outlier_share = 0.0;  // this share of the points replaced by uniform ones over the window, z in [-20, 10]
  std::uint64_t seed = 1;

  // False (and why) for a non-finite or non-positive size, a window outside [0, 1] or empty, no points, negative
  // noise or an outlier share outside [0, 1).
  bool IsValid(std::string* error) const;
};

// The workpiece's height at (x, y), mm (the noise-free surface; 0 on the top face).
double workpiece_height(const WorkpieceOptions& options, double x_mm, double y_mm);

// `points` random samples over the window, with noise and outliers, in the workpiece's frame. Throws
// conform::Error when the options are not valid.
std::vector<Eigen::Vector3d> workpiece_samples(const WorkpieceOptions& options);

}  // namespace conform
