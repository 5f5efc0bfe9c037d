#pragma once
// The local geometry at each path point (Lind & Ystgaard 2020, Sec. 4): the outward surface normals of the stub,
// n_s, and of the leg, n_l, each the smallest principal direction of the k nearest vertices of its mesh (PCA), the
// seam tangent t = normalize(n_s x n_l) (Eq. 3) and the leg's in-surface direction away from the stub,
// t_l_out = n_l x t (Eq. 6). Everything in the stub frame S. "Outward" is away from each tube's axis, whichever way
// the mesh's faces wind (the stub is scanned from inside).

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform {

// A tube's axis in the stub frame, to orient the normals.
struct TubeAxis {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit
};

// How a normal is fitted to the k nearest vertices. kPlane is the paper's: the smallest principal direction (the
// normal of the neighbourhood's centroid, off by (distance of the centroid from p) / radius on a curved surface).
// kQuadric (default, beyond the paper) fits a quadratic height field h(x, y) over the PCA plane, centred at p, and
// takes its normal at p: exact to second order, so a cylinder's normal comes out within hundredths of a degree.
enum class NormalFit { kPlane, kQuadric };

struct JointGeometryOptions {
  // Vertices per normal fit, >= 3 (>= 6 for kQuadric, else it falls back to the plane). 0 (default): sized to each
  // mesh's noise sigma and median edge e near the path (scan_quality.h), so that the normal's noise error is about
  // target_normal_deg: N = 3.8 sigma / (e theta) vertices (a disk of N vertices of 0.87 e^2 each, radius r, tilts by
  // 2 sigma / (r sqrt(N))), within [kMinNormals, kMaxNormals].
  int k_normals = 0;
  double target_normal_deg = 0.1;
  double target_tangent_deg = 0.35;  // sized fits grow where the tangent's noise error (1 / sin beta) exceeds this
  static constexpr int kMinNormals = 40;
  static constexpr int kMaxNormals = 800;
  NormalFit fit = NormalFit::kQuadric;
  // Beyond the paper: each path point is moved onto the intersection of the two local surface fits (k_refine
  // nearest vertices of each mesh), within the half-plane of its azimuth (so phi is kept), by Newton's method. This
  // averages the scanner noise of k vertices instead of taking one facet's. 0: off (the paper's point); < 0
  // (default): the normals' k of each mesh.
  int k_refine = -1;
  // A refinement that would move a point farther than this, or than half the radius of the smaller local patch
  // (k_refine vertices; the fits hold within it), is not applied.
  double max_refine_mm = 3.0;
  bool IsValid(std::string* error) const;
};

// One point of the path (its point refined when k_refine > 0): the quintuplet (phi, p, t, n_s, n_l) of Eq. (4), plus
// t_l_out.
struct PathFrame {
  double phi_rad = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d tangent = Eigen::Vector3d::UnitX();
  Eigen::Vector3d stub_normal = Eigen::Vector3d::UnitX();
  Eigen::Vector3d leg_normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d leg_out = Eigen::Vector3d::UnitY();  // t_l_out, Eq. (6)
  // 1-sigma errors the scans' noise leaves (LocalQuadric::normal_sigma_rad): each normal's, and the tangent's,
  // sqrt((sigma_s^2 + sigma_l^2) / 2) / sin(beta) for the angle beta between the normals (Eq. 3 amplifies the tilt
  // across the seam, one of each normal's two components, by 1 / sin beta).
  double stub_normal_sigma_deg = 0.0, leg_normal_sigma_deg = 0.0, tangent_sigma_deg = 0.0;
};

// Vertices per normal fit for a mesh of this noise and median edge (JointGeometryOptions::k_normals = 0).
int sized_normal_count(double noise_mm, double edge_mm, const JointGeometryOptions& options);

// The outward unit normal at p from the PCA of the given points (their smallest principal direction), oriented away
// from the axis. Throws conform::Error with fewer than 3 points.
Eigen::Vector3d pca_normal(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& p, const TubeAxis& axis,
                           NormalFit fit = NormalFit::kQuadric);

// Moves p onto both patches (stub and leg) within the half-plane of its azimuth about z; false (p unchanged) when
// Newton's method does not converge or would move it farther than max_move_mm.
struct LocalQuadric;
bool refine_seam_point(const LocalQuadric& stub, const LocalQuadric& leg, double max_move_mm, Eigen::Vector3d* p);

// Eq. (3) and (6) from the two normals. Throws conform::Error when they are parallel (the surfaces touch, no seam).
PathFrame path_frame(double phi_rad, const Eigen::Vector3d& p, const Eigen::Vector3d& stub_normal,
                     const Eigen::Vector3d& leg_normal);

// The frames of every path point: normals by PCA of the k nearest vertices of the stub mesh and of the leg mesh
// (both in S). *refined (if given): the points the refinement moved (k_refine > 0). Throws conform::Error when the
// options are invalid or a mesh has fewer than k vertices.
std::vector<PathFrame> joint_geometry(const std::vector<double>& phi_rad, const std::vector<Eigen::Vector3d>& points,
                                      const Mesh& stub_S, const TubeAxis& stub_axis, const Mesh& leg_S,
                                      const TubeAxis& leg_axis, const JointGeometryOptions& options,
                                      std::size_t* refined = nullptr);

}  // namespace conform
