#pragma once
// A synthetic eroded turbine-blade surface for `conform weld-layers`: a smooth doubly curved, twisted sheet
//   h(x, y) = -x^2 / (2 R_chord) - y^2 / (2 R_span) + twist x y   (convex seen from +z, the outward side)
// over [-length/2, length/2] x [-width/2, width/2], with craters (cavitation pits) pressed in along the normal,
//   depth(rho) = D (1 - (rho / a)^2)^3 for rho < a   (rho the distance from the crater centre in x, y),
// smooth (C2: no jump of curvature) at the rim rho = a. A ring-shaped crater (inner radius b > 0) has the same profile
// across its annulus: depth = D (1 - (s / h)^2)^3, s = |rho - (a + b) / 2|, h = (a - b) / 2. A crater may carry a
// raised lip beyond its rim, height L sin^2(pi (rho - a) / w) for a < rho < a + w; bumps (spatter, deposits) are
// raised with the crater profile. The reference grid may be offset along z and tilted about y against the eroded
// one (a registration error: the eroded grid stays the truth). Sampled on a rows x cols grid (row along y, col along x), the eroded grid with
// Gaussian noise along z, the reference grid without. A depth threshold t cuts the crater at
// rho_t = a sqrt(1 - cbrt(t / D)): the rim the intersection should find.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace conform {

struct Crater {
  double x_mm = 0.0, y_mm = 0.0;  // centre
  double radius_mm = 15.0;        // a
  double depth_mm = 2.0;          // D
  double inner_radius_mm = 0.0;   // b: > 0 makes a ring-shaped crater over b < rho < a
  double lip_mm = 0.0;            // L: height of a raised lip beyond the rim
  double lip_width_mm = 0.0;      // w: its width (> 0 when L > 0)
  double radius_y_mm = 0.0;       // > 0: an elongated (elliptic) crater, semi-axes radius_mm along x and this along y:
                                  // depth = D (1 - q)^3, q = (dx / a)^2 + (dy / a_y)^2 (no ring, no lip)
};

struct Bump {
  double x_mm = 0.0, y_mm = 0.0;  // centre
  double radius_mm = 5.0;
  double height_mm = 1.0;         // raised with the crater profile
};

struct ErodedOptions {
  int rows = 41;                 // grid rows (along y)
  int cols = 61;                 // grid columns (along x)
  double length_mm = 120.0;      // extent along x
  double width_mm = 80.0;        // extent along y
  double chord_radius_mm = 150.0;  // R_chord: curvature radius along x
  double span_radius_mm = 400.0;   // R_span: curvature radius along y
  double twist_per_mm = 0.002;     // twist: z += twist x y (1/mm)
  std::vector<Crater> craters = std::vector<Crater>(1);  // one default crater (no initializer list: GCC 12 warns)
  std::vector<Bump> bumps;
  double reference_offset_mm = 0.0;  // the reference grid moved along +z
  double reference_tilt_deg = 0.0;   // and tilted about the y axis (z += tan(tilt) x)
  double noise_mm = 0.01;          // sigma of the eroded grid's noise along z
  std::uint64_t seed = 1;
  int rim_points = 180;            // points per ground-truth rim

  bool IsValid(std::string* error) const;
};

struct ErodedScan {
  int rows = 0, cols = 0;
  std::vector<Eigen::Vector3d> eroded;     // row-major, rows x cols
  std::vector<Eigen::Vector3d> reference;  // row-major, rows x cols
  std::vector<std::vector<Eigen::Vector3d>> rims;  // per crater: the rim rho = a on the reference surface
  double max_depth_mm = 0.0;                       // deepest crater
};

// The blade point and its unit outward normal at (x, y).
Eigen::Vector3d blade_point(const ErodedOptions& options, double x, double y);
Eigen::Vector3d blade_normal(const ErodedOptions& options, double x, double y);
// Depth of all craters at (x, y) (overlapping craters: the deeper one): the damage, the ground truth of the job.
double crater_depth(const ErodedOptions& options, double x, double y);
// Height of the lips and bumps at (x, y) (raised, not damage).
double raised_height(const ErodedOptions& options, double x, double y);

// Throws conform::Error when the options are not valid. Same options, same numbers.
ErodedScan generate_eroded(const ErodedOptions& options);

}  // namespace conform
