#include "inspect/inspect_feature_groups.h"

#include <cmath>
#include <numeric>

namespace conform::detail {

namespace {

double distance_from_axis(const CadFace& axis_of, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - axis_of.origin_mm;
  return (d - d.dot(axis_of.axis) * axis_of.axis).norm();
}

bool same_cylinder(const CadFace& a, const CadFace& b) {
  return a.sense == b.sense && a.axis.cross(b.axis).norm() <= kFeatureSameAxisRad &&
         std::abs(a.radius_mm - b.radius_mm) <= kFeatureSameRadiusMm &&
         distance_from_axis(a, b.origin_mm) <= kFeatureSameAxisMm &&
         distance_from_axis(b, a.origin_mm) <= kFeatureSameAxisMm;
}

std::size_t root_of(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

std::vector<std::vector<std::size_t>> cylinder_features(const std::vector<CadFace>& faces) {
  std::vector<std::size_t> cylinders;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].type == CadSurfaceType::kCylinder) cylinders.push_back(f);
  }
  // Union-find over the pairs on one cylinder; the root is always the group's smallest index.
  std::vector<std::size_t> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (std::size_t i = 0; i < cylinders.size(); ++i) {
    for (std::size_t j = i + 1; j < cylinders.size(); ++j) {
      if (!same_cylinder(faces[cylinders[i]], faces[cylinders[j]])) continue;
      const std::size_t a = root_of(parent, cylinders[i]), b = root_of(parent, cylinders[j]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::size_t> group_of(faces.size(), faces.size());
  for (const std::size_t f : cylinders) {
    const std::size_t root = root_of(parent, f);
    if (group_of[root] == faces.size()) {
      group_of[root] = groups.size();
      groups.emplace_back();
    }
    groups[group_of[root]].push_back(f);
  }
  return groups;
}

CadFace feature_nominal(const std::vector<CadFace>& faces, const std::vector<std::size_t>& group) {
  CadFace out = faces[group.front()];
  out.triangles = 0;
  out.area_mm2 = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (const std::size_t f : group) {
    out.triangles += faces[f].triangles;
    out.area_mm2 += faces[f].area_mm2;
    moment += faces[f].area_mm2 * faces[f].centre_mm;
  }
  if (out.area_mm2 > 0.0) out.centre_mm = moment / out.area_mm2;
  const CadFace& first = faces[group.front()];
  out.origin_mm = first.origin_mm + (out.centre_mm - first.origin_mm).dot(first.axis) * first.axis;
  return out;
}

}  // namespace conform::detail
