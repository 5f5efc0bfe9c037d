#pragma once
// `generate tube`: a synthetic scan of a tube (a patch or the full turn, outer or inner surface) with deformations
// and scanner effects, and its exact ground truth. Frame conventions and the surface formula: tube_options.h.
//
//   TubeOptions options;
//   options.radius_mm = 1000.0;  options.arc_rad = M_PI / 3;  options.vertex_count = 50000;
//   options.noise_mm = 0.05;     options.seed = 7;
//   const TubeScan scan = generate_tube(options);  // scan.mesh in the world frame, scan.truth to compare against

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "conform/core/mesh.h"
#include "conform/datasets/tube_grid.h"
#include "conform/datasets/tube_options.h"
#include "conform/datasets/tube_surface.h"

namespace conform {

struct TubeTruth {
  TubeOptions options;  // as given (without the progress callback)
  TubeGrid grid;        // the layout actually used (columns, rows, edge length)
  Eigen::Isometry3d T_world_tube = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();       // world; the middle of the straight (unbowed) axis
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();  // world, unit: the tube's +z
  double radius_mm = 0.0;                                     // nominal radius R
  std::vector<TubeHole> holes;                                // every hole cut: the given ones, then the random ones
  std::vector<std::int32_t> outlier_indices;                  // vertices moved as outliers, ascending

  // Per vertex of the final mesh (after the holes):
  std::vector<Eigen::Vector2d> vertex_parameters;  // (theta rad, z mm) on the surface
  std::vector<Eigen::Vector3d> exact_vertices;     // world; on the deformed surface, before noise and outliers
};

struct TubeScan {
  Mesh mesh;  // world frame, mm
  TubeTruth truth;
};

// Throws conform::Error when the options are not valid (the message says which and why), when the random holes do
// not fit on the surface, or when the holes remove every face.
TubeScan generate_tube(const TubeOptions& options);

}  // namespace conform
