#pragma once
// The fixed side of a registration, prepared once and shared by every start and every ICP run against it: the
// reference points in double, one unit normal per point, a kd-tree over the points (and both again in the tree's
// leaf order, for fast pairing) and, for a mesh, an index over its triangles (point-to-surface), built on first use.
// Thread-safe to query.

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "conform/core/cloud.h"
#include "conform/core/mesh.h"
#include "conform/core/nearest_neighbors.h"
#include "conform/core/phong_surface.h"
#include "conform/core/triangle_index.h"

namespace conform {

class IcpReference {
 public:
  // Normals: the mesh's own when it has them, else area-weighted from its faces, else PCA over 16 neighbours
  // (turned away from the centroid).
  // Throws conform::Error when the mesh has fewer than 3 points or a non-finite one.
  explicit IcpReference(const Mesh& reference);
  explicit IcpReference(const Cloud& reference);
  ~IcpReference();
  IcpReference(IcpReference&&) noexcept;
  IcpReference& operator=(IcpReference&&) noexcept;

  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  const std::vector<Eigen::Vector3d>& normals() const { return normals_; }
  const KdTree& tree() const { return *tree_; }
  // A point and its normal, stored in the tree's leaf order: by_position()[p] is point tree().leaf_order()[p], so
  // that what KdTree::nearest_position finds for nearby queries is read from nearby memory.
  struct Sample {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  };
  const std::vector<Sample>& by_position() const { return by_position_; }
  bool has_surface() const { return !faces_.empty(); }
  const std::vector<Face>& faces() const { return faces_; }
  // Per vertex of a mesh: 1 when every face around it is within the crease angle of its normal and of each other (a
  // smooth surface there; core/phong_surface.h smooth_vertices), 0 at a crease or corner (a CAD edge) and for a
  // vertex without faces. Empty for a cloud. Builds the smooth surface (phong()) on the first call.
  const std::vector<unsigned char>& smooth() const;
  // Builds the triangle index on the first call (or waits for prepare_surface's build). Throws conform::Error when
  // the reference has no faces.
  const TriangleIndex& surface() const;
  // When OpenMP may use more than one thread: starts building surface() and phong() on another thread, so that the
  // build overlaps whatever the caller does meanwhile (align's coarse stage, which is mostly serial). Nothing for a
  // cloud, or with one thread (surface() then builds on first use, as without this call).
  void prepare_surface() const;
  // The smooth surface over the faces (core/phong_surface.h) with these normals; built with surface(), same throws.
  const PhongSurface& phong() const;
  std::size_t size() const { return points_.size(); }

 private:
  void build(Mesh mesh);

  std::vector<Eigen::Vector3d> points_;
  std::vector<Eigen::Vector3d> normals_;
  std::vector<Face> faces_;
  std::vector<Sample> by_position_;
  std::unique_ptr<KdTree> tree_;
  struct SurfaceState;
  Mesh surface_mesh() const;
  std::unique_ptr<SurfaceState> surface_state_;  // last: its pending build is joined before the rest goes
};

}  // namespace conform
