#pragma once
// Closest points on a triangle mesh's surface (not only its vertices): a bounding-volume hierarchy over the
// triangles, queried for the nearest surface point. Used by point-to-surface ICP (registration/) and by the signed
// deviation of a scan from its reference (evaluation/).
//
//   const TriangleIndex index(reference);                // throws conform::Error for a mesh without faces
//   const SurfacePoint s = index.closest(p, 5.0);         // nearest surface point within 5 mm, or !s.found()
//   const double signed_mm = (p - s.point).dot(index.normal_at(s)) >= 0 ? std::sqrt(s.sq_distance)
//                                                                       : -std::sqrt(s.sq_distance);

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "conform/core/mesh.h"

namespace conform {

// Where on its triangle a closest point lies: the sign of a distance needs the right normal for each case.
enum class TriangleFeature { kFace, kEdge01, kEdge12, kEdge20, kVertex0, kVertex1, kVertex2 };

struct SurfacePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();        // closest point on the surface, mm
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();  // weights of the face's three vertices
  int face = -1;                                          // -1 when nothing was found within the search distance
  TriangleFeature feature = TriangleFeature::kFace;
  double sq_distance = std::numeric_limits<double>::infinity();  // mm^2

  bool found() const { return face >= 0; }
};

// The closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5: Voronoi regions of
// the vertices, edges and face). `face` is left at -1 (the caller knows which face it asked about). A triangle
// without area (collinear or coincident vertices; |ab x ac| below 1e-12 of its longest edge squared) is treated as
// its three edges, so the answer is the closest point on the segment or point it really is.
SurfacePoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

class TriangleIndex {
 public:
  // Keeps its own copy of what it needs; the mesh may go away. Throws conform::Error for a mesh without faces, a face
  // index out of range or a NaN/infinite vertex. Faces without area are allowed (their closest points lie on their
  // edges). Build cost O(n log n); memory about 175 bytes per face (with a copy of the mesh, for the pseudo-normals
  // made on first use).
  explicit TriangleIndex(const Mesh& mesh);
  ~TriangleIndex();
  TriangleIndex(TriangleIndex&&) noexcept;
  TriangleIndex& operator=(TriangleIndex&&) noexcept;

  std::size_t face_count() const;

  // The closest surface point to `query` no farther than max_distance (mm, inclusive); found() is false when there
  // is none. The answer is the smallest (squared distance, face index) over all faces, exactly what a loop over
  // closest_point_on_triangle gives: ties go to the lower face index, and results are deterministic. Thread-safe.
  // Throws conform::Error for a NaN/infinite query or a negative or NaN max_distance.
  SurfacePoint closest(const Eigen::Vector3d& query,
                       double max_distance = std::numeric_limits<double>::infinity()) const;

  // For repeated queries near one place (ICP's late iterations move each point by micrometres): closest(query,
  // max_distance), its reach r = max(its distance, min_reach) in *reach, and in `slots` every triangle within
  // distance + 2 r of `query`, at most max_slots (slots is left empty when there are more, or when nothing was
  // found). While a later query x stays within r of `query`, its closest surface point is on one of those triangles
  // (the triangle inequality), and closest_among(x, slots, max_distance) returns exactly what closest(x,
  // max_distance) would. Slots are this index's own handles for triangles, meaningful only to it.
  SurfacePoint closest_with_slots(const Eigen::Vector3d& query, double max_distance, double min_reach,
                                  std::size_t max_slots, std::vector<std::int32_t>& slots, double* reach) const;
  SurfacePoint closest_among(const Eigen::Vector3d& query, const std::int32_t* slots, std::size_t count,
                             double max_distance) const;

  // Outward normal at a closest point: the face normal inside a face, the angle-weighted pseudo-normal of the
  // vertex or edge otherwise (Baerentzen & Aanaes 2005), so that sign(dot(query - point, normal)) is the side of a
  // closed or open surface the query lies on, even where the closest point is an edge or a vertex. Unit length;
  // "outward" is the side the faces' counter-clockwise winding points to. Where a pseudo-normal cancels out (a sheet
  // folded onto itself) the face's own normal is used; zero only for a face without area whose neighbours have none
  // either, and for a point that was not found.
  Eigen::Vector3d normal_at(const SurfacePoint& point) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace conform
