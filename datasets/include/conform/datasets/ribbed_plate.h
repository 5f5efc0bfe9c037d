#pragma once
// A machined plate with ribs, as a height field (a laser profiler looking down sees no vertical wall), sampled at
// random: two independent samplings are a scan and a reference cloud of the same surface whose points do not
// coincide. Its ribs run along y and stop short of the plate's ends, so the plate constrains translation along y
// only through the ribs' sloped ends: a weak but real constraint (registration/degeneracy.h).
//
// Height, mm, over x in [-length/2, length/2], y in [-width/2, width/2]:
//   z = sum over ribs k of rib_height * s(x - x_k, rib_width / 2) * s(y, rib_length / 2),
//   s(u, h) = smoothstep((h + ramp - |u|) / ramp), smoothstep(t) = 3t^2 - 2t^3 on [0, 1] (1 inside, 0 outside),
// ribs at x_k = (k - (n - 1) / 2) * rib_pitch.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct RibbedPlateOptions {
  double length_mm = 200.0;    // along x
  double width_mm = 150.0;     // along y
  int ribs = 4;                // along y, spaced along x
  double rib_pitch_mm = 40.0;  // between ribs' centre lines
  double rib_width_mm = 6.0;   // at the top
  double rib_height_mm = 8.0;
  double rib_length_mm = 100.0;  // along y, centred: the ends are the only features along y
  double ramp_mm = 1.0;          // horizontal run of the rib walls and ends (steep, not vertical)
  std::size_t points = 100000;   // uniform in x and y
  double noise_mm = 0.02;        // Gaussian along z, sigma
  std::uint64_t seed = 1;

  // False (and why) for a non-finite or non-positive size, ribs that do not fit on the plate, no points or negative
  // noise.
  bool IsValid(std::string* error) const;
};

// The plate's height at (x, y), mm (the noise-free surface).
double ribbed_plate_height(const RibbedPlateOptions& options, double x_mm, double y_mm);

// Its unit upward normal at (x, y).
Eigen::Vector3d ribbed_plate_normal(const RibbedPlateOptions& options, double x_mm, double y_mm);

// `points` random samples of the surface with noise, in the plate's frame. Throws conform::Error when the options
// are not valid.
std::vector<Eigen::Vector3d> ribbed_plate_samples(const RibbedPlateOptions& options);

}  // namespace conform
