#pragma once
// Surface normals by principal component analysis: the eigenvector of the smallest eigenvalue of the covariance of
// each point's k nearest neighbours (the point itself included; accumulated in double, centred on the neighbourhood
// mean), oriented consistently. Runs in parallel (OpenMP); the result does not depend on the number of threads.
// Degenerate neighbourhoods get a defined, NaN-free normal with curvature 0: when all neighbours coincide, the unit
// orientation reference direction (towards the viewpoint, away from / towards the axis, the vertex's face normal);
// when they are collinear, the part of that direction perpendicular to the line. If that is zero too, the solver's
// smallest eigenvector: a deterministic unit vector (perpendicular to the line, if there is one).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cloud.h"
#include "conform/core/mesh.h"
#include "conform/core/nearest_neighbors.h"

namespace conform {

enum class NormalOrientation {
  kTowardsViewpoint,  // n . (viewpoint - p) >= 0 (a scanner's position)
  kAwayFromAxis,      // n . (p - its projection on the axis) >= 0 (the outer surface of a tube)
  kTowardsAxis,       // the inner surface of a tube
};

struct NormalOptions {
  int k = 16;  // neighbours per point, >= 3 (all points if fewer)
  // Take, for a point whose k neighbours straddle a step or crease, the plane of a neighbour's much flatter
  // neighbourhood that the point lies on (normals.cpp, flattest_neighbourhoods): the normal of the point's own side,
  // not a tilt between the sides. False: plain PCA over the point's own neighbours. Off by default and at every call
  // site: better on the ribbed plate's ICP and the real small_gicp pair, worse on the sparsely sampled workpiece
  // (docs/align.md, "Normals at steps and creases").
  bool flattest_neighbourhood = false;
  NormalOrientation orientation = NormalOrientation::kTowardsViewpoint;
  Eigen::Vector3d viewpoint = Eigen::Vector3d::Zero();        // mm
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();       // mm, for the axis orientations
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();  // any length > 0

  bool IsValid(std::string* error) const;
};

// Unit normals of every point; curvature holds the surface variation l0 / (l0 + l1 + l2) (l0 the smallest eigenvalue)
// of the neighbourhood the normal was taken from.
// Throws conform::Error when options are invalid, the cloud has fewer than 3 points or a non-finite point.
pcl::PointCloud<pcl::Normal> estimate_normals(const Cloud& cloud, const NormalOptions& options);

// The same for the points of a tree already built over them (KdTree keeps its own float copy): normals[i] is that of
// the tree's point i, equal bit for bit to estimate_normals of those points as a cloud, without a second tree. The
// queries run in the tree's leaf order, so that each finds the last one's neighbours still in cache.
pcl::PointCloud<pcl::Normal> estimate_normals(const KdTree& tree, const NormalOptions& options);

// PCA normals of a mesh's vertices over their k nearest vertices, each oriented to agree with the
// area-weighted normal of the faces around that vertex (vertex_normals_from_faces); a vertex without faces uses the
// sum of its neighbours' face normals, and keeps the PCA sign when that is zero too. Throws conform::Error when k < 3,
// the mesh has fewer than 3 vertices, no faces, a bad face index or a non-finite vertex.
std::vector<Eigen::Vector3d> estimate_normals(const Mesh& mesh, int k = 16);

}  // namespace conform
