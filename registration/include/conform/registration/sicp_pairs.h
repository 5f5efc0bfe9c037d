#pragma once
// Subdivision-ICP's pairs: the closest point of a reference (on its triangles when it has faces, else its nearest
// point with that point's normal). Also used by the projection model (compensation/projection_model.h).

#include <cmath>

#include <Eigen/Core>

#include "conform/registration/icp_reference.h"

namespace conform {

struct ReferencePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  bool found = false;
};

// Not found when nothing lies within max_distance_mm. At a triangle's edge or vertex the normal is the direction
// to x, so that the signed distance n . (x - point) is the Euclidean one.
inline ReferencePoint closest_on_reference(const IcpReference& reference, const Eigen::Vector3d& x,
                                           double max_distance_mm) {
  ReferencePoint r;
  if (reference.has_surface()) {
    const SurfacePoint s = reference.surface().closest(x, max_distance_mm);
    if (!s.found()) return r;
    r.point = s.point;
    r.normal = reference.surface().normal_at(s);
    // At an edge or vertex the pseudo-normal is not perpendicular to x - point; the distance is then Euclidean.
    const Eigen::Vector3d d = x - s.point;
    if (d.norm() > 1e-12 && std::abs(r.normal.dot(d.normalized())) < 0.999) r.normal = d.normalized();
    r.found = true;
    return r;
  }
  float sq = 0.0f;
  const int i = reference.tree().nearest(x.cast<float>(), &sq);
  if (i < 0 || static_cast<double>(sq) > max_distance_mm * max_distance_mm) return r;
  r.point = reference.points()[static_cast<std::size_t>(i)];
  r.normal = reference.normals()[static_cast<std::size_t>(i)];
  r.found = true;
  return r;
}

}  // namespace conform
