#pragma once
// What a scan is like near the seam, measured on the mesh itself: its noise (RMS of the vertices about local
// quadric fits, local_quadric.h), its edge length, and its curvature. The tube-joint pipeline scales its backtrack
// tolerance by them and warns when a mesh is too coarse for its curvature (its facets then bend the normals by
// edge x curvature, and the refinement onto local fits cannot fix every point).

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform {

struct ScanQuality {
  double noise_mm = 0.0;                 // median over the sample points of the RMS residual of the local quadric fit
  double edge_mm = 0.0;                  // median edge length of the mesh's faces
  double curvature_per_mm = 0.0;         // median of the largest principal curvature of the fits, 1/mm
  double edge_angle_deg = 0.0;           // edge_mm x curvature: how far the normals turn over one edge, deg
  std::size_t samples = 0;               // sample points used
  std::vector<Eigen::Vector3d> normals;  // the fits' unit normals at the sample points (sign arbitrary)
};

// The smallest sine of the angle between two scans' surfaces over the sample points both were estimated at (the
// same points and max_samples give the same samples): where the seam's position is most sensitive to noise.
double min_crossing_sine(const ScanQuality& a, const ScanQuality& b);

// At up to max_samples of `points` (evenly spread), from the k nearest vertices of the mesh. Throws conform::Error
// when the mesh has fewer than 6 vertices or k < 6.
ScanQuality estimate_scan_quality(const Mesh& mesh, const std::vector<Eigen::Vector3d>& points, int k = 40,
                                  std::size_t max_samples = 48);

}  // namespace conform
