#pragma once
// What `generate tube` makes: a cylinder surface (patch or closed tube), its deformations and the scanner's effects.
//
// The tube frame: z is the straight (unbowed) axis, the tube spans z in [-length/2, +length/2], so the frame's
// origin is the middle of the axis; the azimuth theta is measured from the frame's x axis towards its y axis
// (right-handed about z). T_world_tube places the tube in the world (p_world = T_world_tube * p_tube); build it
// from an axis point, an axis direction and an azimuth reference with tube_frame().
//
// The deformed surface (tube frame), with the nominal radius R and e_r = (cos theta, sin theta, 0):
//   r(theta, z) = R + ovality(theta) + seam(theta) + sum of bumps(theta, z)
//   S(theta, z) = r(theta, z) e_r + z e_z + bow(z) (cos phi_b, sin phi_b, 0)
// Heights are radial: positive moves the surface away from the axis, for the outer and the inner surface alike.
// Arc lengths (seam width, bump and hole radii) are measured on the nominal cylinder: s = R * delta_theta.

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/progress.h"

namespace conform {

// Which side of the wall is scanned: face normals point away from the axis (outer) or towards it (inner).
enum class TubeSurface { kOuter, kInner };
enum class NoiseDistribution { kGaussian, kUniform };
// Along the exact surface normal (what a triangulation scanner's error mostly is), or the same in every direction.
enum class NoiseDirection { kNormal, kIsotropic };

// A local bump (height > 0) or indentation (height < 0) with a raised-cosine profile:
// h (1 + cos(pi d / rho)) / 2 for d < rho, where d is the distance on the unrolled nominal cylinder.
struct TubeBump {
  double azimuth_rad = 0.0;
  double z_mm = 0.0;
  double height_mm = 0.0;  // radial, signed
  double radius_mm = 0.0;  // rho: where the profile returns to zero (> 0)
};

// A missing patch of the scan: every face whose centre lies within radius_mm (on the unrolled nominal cylinder) of
// (azimuth, z) is dropped.
struct TubeHole {
  double azimuth_rad = 0.0;
  double z_mm = 0.0;
  double radius_mm = 0.0;
};

struct TubeOptions {
  // --- geometry ---
  double radius_mm = 150.0;     // nominal radius R (> 0)
  double length_mm = 300.0;     // along the axis; z in [-length/2, +length/2]
  double arc_rad = 2.0 * M_PI;  // azimuth span in (0, 2 pi]; 2 pi gives a closed tube without a seam of faces
  double arc_center_rad = 0.0;  // a patch covers [center - arc/2, center + arc/2]
  TubeSurface surface = TubeSurface::kOuter;
  Eigen::Isometry3d T_world_tube = Eigen::Isometry3d::Identity();

  // --- triangulation: staggered rows of near-equilateral triangles, like a scanner's mesh ---
  double edge_mm = 5.0;           // target edge length
  std::int64_t vertex_count = 0;  // > 0: choose the edge length so that the mesh has about this many vertices
  bool vertex_normals = false;    // store per-vertex normals (area-weighted from the final faces)

  // --- deformations (see the surface formula above) ---
  double ovality_mm = 0.0;           // a in a cos 2(theta - theta0): D_max - D_min = 4a
  double ovality_azimuth_rad = 0.0;  // theta0, where the radius is largest (for a > 0)
  double seam_height_mm = 0.0;       // peaking at the weld seam, radial and signed (0: no seam)
  double seam_width_mm = 20.0;       // full base width of the ridge, arc length; raised cosine, C1 at its edges
  double seam_azimuth_rad = 0.0;     // theta_s
  std::vector<TubeBump> bumps;
  double bow_mm = 0.0;           // sagitta s at mid-length: bow(z) = s (1 - (2z/L)^2), zero at both ends
  double bow_azimuth_rad = 0.0;  // phi_b, the direction (in the tube's xy plane) the middle moves to

  // --- scanner effects, applied after the triangulation in this order: holes, noise, outliers ---
  double noise_mm = 0.0;  // gaussian: sigma; uniform: half-width a (values in [-a, a])
  NoiseDistribution noise_distribution = NoiseDistribution::kGaussian;
  NoiseDirection noise_direction = NoiseDirection::kNormal;  // isotropic uniform: uniform in a ball of radius a
  std::vector<TubeHole> holes;                               // given holes
  int random_holes = 0;  // more holes at seeded random places, inside the surface, not overlapping
  double random_hole_radius_mm = 10.0;
  double outlier_fraction = 0.0;     // in [0, 1): this share of the vertices is displaced along the normal
  double outlier_distance_mm = 5.0;  // an outlier moves by d to 2d, towards either side at random

  std::uint64_t seed = 1;  // the same options and seed give the same mesh, bit for bit
  ProgressFn progress;     // stages "tube: vertices", "tube: faces", "tube: scanner effects"

  // False (and why, naming the option) when a value is out of range, non-finite or the mesh would be too large.
  bool IsValid(std::string* error) const;
};

// Most triangles generate_tube makes (a guard against a mistyped edge length exhausting memory).
inline constexpr double kMaxTubeTriangles = 100e6;

// T_world_tube from the axis (a point on it, which becomes the tube's middle, and its direction, the tube's +z) and
// an azimuth reference: a world direction whose component perpendicular to the axis becomes the tube's x (theta = 0).
// Throws conform::Error when the direction is zero or the reference is (nearly) parallel to the axis.
Eigen::Isometry3d tube_frame(const Eigen::Vector3d& axis_point, const Eigen::Vector3d& axis_direction,
                             const Eigen::Vector3d& azimuth_reference);
// The default azimuth reference: the world axis (x, then y, then z) least aligned with the tube's axis.
Eigen::Vector3d default_azimuth_reference(const Eigen::Vector3d& axis_direction);

}  // namespace conform
